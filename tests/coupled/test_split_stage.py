#!/usr/bin/python3
"""wall_after (a coupled run's wall cells made thin part way through, docs/RAMAIR.md): the settings it needs are
checked with the file and line (coupled yes, wall_split or wall_layers, below steps), and ramair_fluid.py
split-stage tells Allrun's remesh loop what a new mesh at time T gets: plain before wall_after's time, N splits or
the layers from it on, and that stage's step, write interval and equilibrium steps only for the new mesh that
starts it
(the controlDict's step still the unsplit one); mesh-gate stops the loop on a new mesh that fails checkMesh
in anything but the skewness; split-exclude turns a split mesh's wrong-oriented faces into spots left unsplit.
Usage: test_split_stage.py SOURCE_DIR WORK"""
import json
import os
import subprocess
import sys

src, work = sys.argv[1], sys.argv[2]
import shutil
shutil.rmtree(work, ignore_errors=True)  # split-exclude keeps its spots in the work folder: start without any
os.makedirs(os.path.join(work, "constant"), exist_ok=True)
gen = os.path.join(src, "cases/coupled/ramair_fluid.py")
bad = []


def call(*args):
    p = subprocess.run(["/usr/bin/python3", gen, *args], capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


def expect(name, ok, detail):
    print(("ok   " if ok else "FAIL ") + f"{name}: {detail}")
    if not ok:
        bad.append(name)


def settings(text):
    path = os.path.join(work, "s.settings")
    with open(path, "w") as f:
        f.write("speed 15\ncourant 4\nsteps 700\ncoupled yes\n" + text)
    return path


for name, text, want in (
        ("needs wall_split or wall_layers", "wall_after 400\n", "s.settings:5: wall_after needs coupled yes and wall_split or wall_layers"),
        ("below steps", "wall_split 2\nwall_after 700\n", "s.settings:6: wall_after 700 must be below steps 700"),
        ("split from the start needs a small step", "wall_split 2\n", "s.settings:5: wall_split 2 with coupled yes "
         "needs courant <= 1 (4 / 4"),
        ("layers from the start need a small step", "wall_layers 3\n", "s.settings:5: wall_layers 3 with coupled yes "
         "needs courant <= 1 (4 / 4"),
        ("not both", "wall_split 1\nwall_layers 3\nwall_after 400\n", "s.settings:6: wall_split and wall_layers exclude"),
        ("split later at the main job's step", "wall_split 2\nwall_after 400\n", None)):
    rc, out, err = call("check", settings(text))
    if want is None:
        expect(name, rc == 0 and " wall_after=400 " in out, f"exit {rc} {err.strip()}")
    else:
        expect(name, rc == 2 and want in err, f"exit {rc} {err.strip()}")

# split-stage on a record as `write` leaves it (constant/fluidSettings.json): step 0.01 s, split after 400
dt = 0.01
rec = {"settings": {"wall_split": 2, "wall_layers": 0, "wall_after": 400, "steps": 700, "write_interval": 20,
                    "equilibrium_steps": 200},
       "derived": {"deltaT": dt}}
with open(os.path.join(work, "constant", "fluidSettings.json"), "w") as f:
    json.dump(rec, f)
for name, t, step, want in (
        ("a new mesh before wall_after's time is plain", 2.5, dt, ["split 0", "layers no"]),
        ("wall_after's new mesh starts the split stage", 4.0, dt,
         ["split 2", "layers no", "deltaT 0.0025", "writeInterval 80", "equilibriumSteps 50"]),
        ("a later new mesh is split, the stage already set", 4.5, dt / 4, ["split 2", "layers no"])):
    rc, out, err = call("split-stage", work, str(t), str(step))
    expect(name, rc == 0 and out.split("\n")[:-1] == want, f"exit {rc}: {out.strip()!r} {err.strip()}")
rec["settings"].update({"wall_split": 0, "wall_layers": 3})
with open(os.path.join(work, "constant", "fluidSettings.json"), "w") as f:
    json.dump(rec, f)
rc, out, err = call("split-stage", work, "4.0", str(dt))
expect("wall_layers 3: layers, the step divided by round(1.3^2 / 0.4) = 4", rc == 0 and out.split("\n")[:-1] ==
       ["split 0", "layers yes", "deltaT 0.0025", "writeInterval 80", "equilibriumSteps 50"], repr(out))
rec["settings"].update({"wall_after": 0})
with open(os.path.join(work, "constant", "fluidSettings.json"), "w") as f:
    json.dump(rec, f)
rc, out, err = call("split-stage", work, "1.0", str(dt))
expect("layers from the start: every new mesh layered, the step kept", rc == 0 and out == "split 0\nlayers yes\n", repr(out))

# mesh-gate: a new mesh that fails checkMesh in anything but the trailing edge's skewness stops the remesh
# loop, naming the log and the failed checks (synthetic checkMesh logs in v1912's form)
head = "    cells:            85435\n"
skew = " ***Max skewness = 4.3, 3 highly skew faces detected which may impair the quality of the results\n"
pyr = " ***Error in face pyramids: 33 faces are incorrectly oriented.\n"
for name, text, want in (("skewness only", head + skew + "\nFailed 1 mesh checks.\n", 0),
                         ("wrong-oriented faces", head + pyr + skew + "\nFailed 2 mesh checks.\n", 1),
                         ("clean", head + "\nMesh OK.\n", 0)):
    with open(os.path.join(work, "log.checkMesh.remesh1"), "w") as f:
        f.write(text)
    rc, out, err = call("mesh-gate", work, "log.checkMesh.remesh1")
    ok = rc == want and (want == 0 or ("log.checkMesh.remesh1" in err and "face pyramids: 33 faces" in err))
    expect(f"mesh-gate, {name}", ok, f"exit {rc} {err.strip()}")

# split-exclude: the wrong-oriented faces checkMesh names (constant/polyMesh/sets/wrongOrientedFaces) become
# spots of 3 wall cells that system/topoSetDict leaves unsplit; a wrong face inside a spot doubles its radius.
# A synthetic polyMesh of two faces: face 0 centred at (0.5 0.5 0), face 1 at (2.5 0.5 0); h_wing 0.01.
mesh = os.path.join(work, "constant", "polyMesh")
os.makedirs(os.path.join(mesh, "sets"), exist_ok=True)
os.makedirs(os.path.join(work, "system"), exist_ok=True)
head = "FoamFile { version 2.0; format ascii; class %s; object %s; }\n"
with open(os.path.join(mesh, "points"), "w") as f:
    f.write(head % ("vectorField", "points") + "8\n(\n(0 0 0)\n(1 0 0)\n(1 1 0)\n(0 1 0)\n(2 0 0)\n(3 0 0)\n(3 1 0)\n(2 1 0)\n)\n")
with open(os.path.join(mesh, "faces"), "w") as f:
    f.write(head % ("faceList", "faces") + "2\n(\n4(0 1 2 3)\n4(4 5 6 7)\n)\n")
rec = {"settings": {"wall_split": 2}, "settings_file": os.path.join(work, "s.settings"),
       "derived": {"deltaT": dt, "h_wing": 0.01}, "wing": {"min": [0, -1.5, -0.4], "max": [1, 1.5, 0.1]},
       "domain": {"min": [-8, -10, -8], "max": [17, 10, 8]}}
with open(os.path.join(work, "constant", "fluidSettings.json"), "w") as f:
    json.dump(rec, f)
with open(os.path.join(work, "log.checkMesh.split"), "w") as f:
    f.write("    cells:            85435\n" + pyr + "\nFailed 1 mesh checks.\n")
spheres = []
for name, ids, want in (("two wrong faces: two spots", "2(0 1)", [(0.5, 0.03), (2.5, 0.03)]),
                        ("the first again: its spot doubles", "1(0)", [(0.5, 0.06), (2.5, 0.03)])):
    with open(os.path.join(mesh, "sets", "wrongOrientedFaces"), "w") as f:
        f.write(head % ("faceSet", "wrongOrientedFaces") + ids + "\n")
    rc, out, err = call("split-exclude", work, "log.checkMesh.split")
    with open(os.path.join(work, "system", "topoSetDict")) as f:
        d = f.read()
    import re
    spheres = [(float(a), float(r)) for a, r in
               re.findall(r"sphereToCell; origin \(([-\d.e]+) 0.5 0\); radius ([\d.e]+);", d)]
    ok = rc == 3 and spheres == want and "boxToCell" in d and "(-9 -1.38 -9) (18 1.38 9)" in d
    expect(f"split-exclude, {name}", ok, f"exit {rc}, spheres {spheres} {err.strip()}")
with open(os.path.join(work, "log.checkMesh.split"), "w") as f:
    f.write("    cells:            85435\n" + skew + "\nFailed 1 mesh checks.\n")
rc, out, err = call("split-exclude", work, "log.checkMesh.split")
expect("split-exclude, a mesh that passes: done", rc == 0, f"exit {rc} {err.strip()}")
sys.exit(1 if bad else 0)
