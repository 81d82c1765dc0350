#!/usr/bin/python3
"""The ram-air case's pilot controls (docs/RAMAIR.md): brake_left, brake_right (both: a symmetric or
differential pull) and brake_table (the toggles' travel in time from a CSV file) become prescribed motions of
the toggles in the coupled scene (ramair_fluid.py structure), each toggle released from the held points; bad
tables are refused with the table's file and line. The flow's response to them is the coupled runs'
(fluid.ramair-brake; docs/RAMAIR.md). Usage: test_brake_inputs.py SOURCE_DIR WORK"""
import os
import shutil
import subprocess
import sys

import yaml

src, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
gen = os.path.join(src, "cases/coupled/ramair_fluid.py")
scene = os.path.join(src, "cases/coupled/ramair-kt/structure.yaml")
bad = []


def expect(name, ok, detail):
    print(("ok   " if ok else "FAIL ") + f"{name}: {detail}")
    if not ok:
        bad.append(name)


def run(extra, table=None):
    if table is not None:
        with open(os.path.join(work, "brakes.csv"), "w") as f:
            f.write(table)
    path = os.path.join(work, "s.settings")
    with open(path, "w") as f:
        f.write("speed 15\ncoupled yes\n" + extra)
    out = os.path.join(work, "structure-coupled.yaml")
    if os.path.exists(out):
        os.remove(out)
    p = subprocess.run(["/usr/bin/python3", gen, "structure", path, scene, out], capture_output=True, text=True)
    return p.returncode, p.stderr, (yaml.safe_load(open(out)) if p.returncode == 0 else None)


def toggles(sc):
    """{side: prescribe} of the pulled toggles and the held nodes"""
    pulled, held = {}, []
    for c in sc["constraints"]:
        if "prescribe" in c and str(c["nodes"]).startswith("wing/toggle_"):
            pulled[c["nodes"].split("_")[-1]] = c["prescribe"]
        if c.get("fix") == "all":
            held += c["nodes"] if isinstance(c["nodes"], list) else [c["nodes"]]
    return pulled, held


rc, err, sc = run("")
p, held = toggles(sc)
expect("no brake: both toggles held", rc == 0 and not p and {"wing/toggle_left", "wing/toggle_right"} <= set(held),
       f"pulled {sorted(p)}")
rc, err, sc = run("brake_left 0.2\nbrake_start 1\nbrake_duration 0.5\n")
p, held = toggles(sc)
expect("left brake: the left toggle drawn down by a smooth step, the right one held",
       rc == 0 and list(p) == ["left"] and p["left"]["amplitude"] == 0.2 and p["left"]["direction"] == [0, 0, -1]
       and p["left"]["function"] == {"type": "smooth_step", "start": 1.0, "duration": 0.5}
       and "wing/toggle_right" in held and "wing/toggle_left" not in held, f"{p} held {held}")
rc, err, sc = run("brake_left 0.2\nbrake_right 0.2\n")
p, held = toggles(sc)
expect("symmetric brake: both toggles drawn down alike", rc == 0 and sorted(p) == ["left", "right"]
       and p["left"] == p["right"] and not any("toggle" in h for h in held), f"{p}")
rc, err, sc = run("brake_table brakes.csv\n", "time,left,right\n0,0,0\n1,0,0.1\n2,0.1,0.1\n")
p, held = toggles(sc)
expect("brake_table: each toggle follows its column (m) as a table function",
       rc == 0 and p.get("right", {}).get("function") == {"type": "table", "points": [[0, 0], [1, 0.1], [2, 0.1]]}
       and p.get("left", {}).get("function") == {"type": "table", "points": [[0, 0], [1, 0], [2, 0.1]]}
       and p["left"]["amplitude"] == 1.0, f"{p}")
rc, err, sc = run("brake_table brakes.csv\n", "time,left,right\n0,0,0\n1,0,0.3\n")
p, held = toggles(sc)
expect("a table column that stays 0 keeps its toggle held", rc == 0 and list(p) == ["right"]
       and "wing/toggle_left" in held, f"{p} held {held}")
for name, extra, table, want in (
        ("times must increase", "brake_table brakes.csv\n", "time,left,right\n0,0,0\n0,0,0.1\n",
         "brakes.csv:3: time 0 does not follow 0"),
        ("travel within 0-2 m", "brake_table brakes.csv\n", "time,left,right\n0,0,0\n1,0,2.5\n",
         "brakes.csv:3: right travel 2.5 m is outside [0, 2]"),
        ("the header", "brake_table brakes.csv\n", "t,l,r\n0,0,0\n", "brakes.csv:1: the first line must be the header"),
        ("a missing table", "brake_table nosuch.csv\n", None, "s.settings:3: brake_table nosuch.csv: cannot read it"),
        ("table and brake_right", "brake_right 0.1\nbrake_table brakes.csv\n", "time,left,right\n0,0,0\n",
         "s.settings:3: brake_right with brake_table"),
        ("no commands in a file name", "brake_table $(ls)\n", None, "brake_table '$(ls)': a file name of")):
    rc, err, _ = run(extra, table)
    expect(f"refused: {name}", rc == 2 and want in err, f"exit {rc} {err.strip()}")
sys.exit(1 if bad else 0)
