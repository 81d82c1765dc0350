#!/usr/bin/python3
"""ramair_fluid.py courant-check (Allrun runs it after every pimpleFoam run): a log whose Courant number ran
past 100 x the settings' `courant` or became NaN stops the case naming the step; a sane log passes; a missing
log is refused naming it. Synthetic logs in the form pimpleFoam writes. Usage: test_courant_check.py SOURCE_DIR WORK"""
import os
import subprocess
import sys

src, work = sys.argv[1], sys.argv[2]
os.makedirs(work, exist_ok=True)
gen = os.path.join(src, "cases/coupled/ramair_fluid.py")
settings = os.path.join(work, "c.settings")
with open(settings, "w") as f:
    f.write("speed 15\ncourant 4\n")
bad = []


def log(name, values):
    path = os.path.join(work, name)
    with open(path, "w") as f:
        for i, v in enumerate(values):
            f.write(f"Courant Number mean: 0.1 max: {v}\nTime = {0.01 * (i + 1):g}\n\nsmoothSolver: ...\n")
    return path


def run(path):
    p = subprocess.run(["/usr/bin/python3", gen, "courant-check", path, settings], capture_output=True, text=True)
    return p.returncode, p.stderr


for name, values, want, text in (
        ("sane", [3.9, 12.5, 13.0], 0, ""),
        ("runaway", [4.0, 45.0, 3.2e3, 6.1e59], 1, "6.1e+59 at t = 0.03 s"),
        ("nan", [4.0, "nan", 5.0], 1, "nan at t = 0.01 s"),
        ("limit", [399.0], 0, "")):
    rc, err = run(log(name, values))
    ok = rc == want and text in err
    print(("ok   " if ok else "FAIL ") + f"{name}: exit {rc} {err.strip()}")
    if not ok:
        bad.append(name)
rc, err = run(os.path.join(work, "missing.log"))
ok = rc == 2 and "missing.log" in err
print(("ok   " if ok else "FAIL ") + f"a missing log is refused naming it: {err.strip()}")
if not ok:
    bad.append("missing")
sys.exit(1 if bad else 0)
