#!/usr/bin/python3
"""The ram-air case's `sideslip` setting (docs/RAMAIR.md "Sideslip"): refused with the file and line where the
flow must stay symmetric or the wing is coupled; the free stream turned about z (checked against the rotation
matrix R_z(-b) applied to the x-z inflow, and against the flight model's sideslip asin(v/V) of the wing's motion
through the air); forceCoeffs' drag along the stream and lift normal to it and to the span; the box's side
faces (y min, y max) in the far-field patch, whose conditions let the stream in on the windward side and out on
the lee side (freestreamVelocity, freestreamPressure, inletOutlet); sideslip 0 writes the same dictionaries as
no sideslip key; the summary's side force, roll and yaw from a forces function object's output. Under 1 s.
Usage: test_sideslip.py SOURCE_DIR WORK"""
import json
import math
import os
import re
import shutil
import subprocess
import sys

src, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
gen = os.path.join(src, "cases/coupled/ramair_fluid.py")
sys.path.insert(0, os.path.join(src, "cases/coupled"))
bad = []


def call(*args, cwd=None):
    p = subprocess.run(["/usr/bin/python3", gen, *args], capture_output=True, text=True, cwd=cwd)
    return p.returncode, p.stdout, p.stderr


def expect(name, ok, detail):
    print(("ok   " if ok else "FAIL ") + f"{name}: {detail}")
    if not ok:
        bad.append(name)


def settings(name, text):
    path = os.path.join(work, name)
    with open(path, "w") as f:
        f.write("speed 15\nmodel kOmegaSST\n" + text)
    return path


# Refusals: the file and the sideslip line, and the line of the key it cannot go with
for name, text, want in (
        ("coupled", "sideslip 5\ncoupled yes\n", "a.settings:3: sideslip 5 with coupled yes (line 4)"),
        ("half domain", "sideslip -5\nhalf_domain yes\n", "a.settings:3: sideslip -5 with half_domain yes (line 4)"),
        ("mirrored mesh", "mirror_mesh yes\nsideslip 2\n", "a.settings:4: sideslip 2 with mirror_mesh yes (line 3)"),
        ("range", "sideslip 31\n", "a.settings:3: sideslip = 31 is outside [-30, 30]")):
    rc, out, err = call("check", settings("a.settings", text))
    expect(f"refused: {name}", rc == 2 and want in err, f"exit {rc} {err.strip()}")

# A closed thin box wing (chord 1 along x, span 3, 0.1 thick) with points on y = 0 for the centre chord
stl = os.path.join(work, "wing.stl")
xs, ys, zs = (0.0, 1.0), (-1.5, 0.0, 1.5), (-0.05, 0.05)
quads = []
for j in range(2):
    y0, y1 = ys[j], ys[j + 1]
    for z in zs:  # lower and upper skins
        quads.append([(0, y0, z), (1, y0, z), (1, y1, z), (0, y1, z)])
    for x in xs:  # leading and trailing faces
        quads.append([(x, y0, zs[0]), (x, y1, zs[0]), (x, y1, zs[1]), (x, y0, zs[1])])
for y in (ys[0], ys[-1]):  # tips
    quads.append([(0, y, zs[0]), (1, y, zs[0]), (1, y, zs[1]), (0, y, zs[1])])
with open(stl, "w") as f:
    f.write("solid wing\n")
    for q in quads:
        for tri in ((q[0], q[1], q[2]), (q[0], q[2], q[3])):
            f.write(" facet normal 0 0 0\n  outer loop\n" + "".join(f"   vertex {p[0]:g} {p[1]:g} {p[2]:g}\n" for p in tri)
                    + "  endloop\n endfacet\n")
    f.write("endsolid wing\n")


def write_case(name, text):
    case = os.path.join(work, name)
    for sub in ("system", "constant", "0"):
        os.makedirs(os.path.join(case, sub))
    path = settings(f"{name}.settings", text)
    rc1, _, e1 = call("write", path, stl, case)
    rc2, _, e2 = call("fields", case)
    if rc1 or rc2:
        expect(f"{name} written", False, e1 + e2)
    return case


def read(case, rel):
    with open(os.path.join(case, rel)) as f:
        return f.read()


def vec(text, pattern):
    m = re.search(pattern + r"\s*\(([^)]*)\)", text)
    return [float(v) for v in m.group(1).split()] if m else None


alpha, beta, speed = 3.0, 5.0, 15.0
case = write_case("slip", f"angle {alpha:g}\nsideslip {beta:g}\n")
u_text = read(case, "0/U")
u = vec(u_text, r"farfield \{ type freestreamVelocity; freestreamValue uniform")
# independent: R_z(-b) (cos a, 0, sin a) as a matrix product
a, b = math.radians(alpha), math.radians(beta)
rz = [[math.cos(-b), -math.sin(-b), 0], [math.sin(-b), math.cos(-b), 0], [0, 0, 1]]
ref = [speed * sum(rz[i][k] * v for k, v in enumerate((math.cos(a), 0.0, math.sin(a)))) for i in range(3)]
expect("the free stream is the x-z inflow turned by -b about z", u is not None and max(abs(u[i] - ref[i]) for i in range(3)) < 1e-7,
       f"U {u}, R_z(-b) U0 {ref}")
expect("the air comes from the right (+y): U_y < 0", u is not None and u[1] < 0, f"U_y {u and u[1]}")
# the flight model's sideslip (flight/FlightSystem.cpp): asin of the y part of the wing's motion through the air
va = [-v for v in u]
fm_beta = math.degrees(math.asin(va[1] / math.sqrt(sum(v * v for v in va))))
expect("the flight model's sideslip asin(cos a sin b)", abs(fm_beta - math.degrees(math.asin(math.cos(a) * math.sin(b)))) < 1e-6
       and fm_beta > 0, f"{fm_beta:.6f} deg")
ctrl = read(case, "system/controlDict")
drag, lift = vec(ctrl, "dragDir"), vec(ctrl, "liftDir")
dot = sum(x * y for x, y in zip(drag, lift))
expect("forceCoeffs: drag along the stream, lift normal to it and to the span",
       max(abs(drag[i] - u[i] / speed) for i in range(3)) < 1e-8 and abs(dot) < 1e-8 and lift[1] == 0 and lift[2] > 0,
       f"dragDir {drag}, liftDir {lift}")
# The side faces: every outer face of the box is `farfield`, nothing symmetric
bm = read(case, "system/blockMeshDict")
verts = [[float(v) for v in m.split()] for m in re.findall(r"^\s*\(([-\d.eE+ ]+)\)\s*$", bm.split("vertices")[1].split(");")[0], re.M)]
faces = re.search(r"farfield \{ type patch; faces \((.*)\); \}", bm).group(1)
faces = [[int(i) for i in f.split()] for f in re.findall(r"\(([\d ]+)\)", faces)]
lo = [min(v[i] for v in verts) for i in range(3)]
hi = [max(v[i] for v in verts) for i in range(3)]
planes = set()
for f in faces:
    for i in range(3):
        for side, val in ((-1, lo[i]), (1, hi[i])):
            if all(abs(verts[k][i] - val) < 1e-9 for k in f):
                planes.add((i, side))
expect("all six faces of the box are the far field (y min and y max too)", len(faces) == 6 and len(planes) == 6
       and "symmetryPlane" not in bm and "mirror" not in bm, f"{len(faces)} faces, planes {sorted(planes)}")
# the stream enters through y max (U . n < 0 there) and leaves through y min: the far field's conditions switch
# by the flux's sign
expect("windward y max takes the stream in, lee y min lets it out", u[1] * 1 < 0 and u[1] * -1 > 0, f"U_y {u[1]:.4g}")
p_text, k_text, om_text = read(case, "0/p"), read(case, "0/k"), read(case, "0/omega")
expect("inlet/outlet conditions on the far field",
       "farfield { type freestreamVelocity" in u_text and "farfield { type freestreamPressure" in p_text
       and "farfield { type inletOutlet" in k_text and "farfield { type inletOutlet" in om_text, "U, p, k, omega")
snappy = read(case, "system/snappyHexMeshDict")
wake = re.search(r"wake \{ type searchableBox;[^}]*\}", snappy).group(0)
wlo, whi = vec(wake, r"min"), vec(wake, r"max")
c = math.sqrt(1.01)  # the centre chord: leading-edge corner to the trailing-edge corner across the thickness
drift = -7 * c * math.tan(b)
expect("the wake box follows the stream sideways (7 chords: 7 c tan b to the left)",
       abs(wlo[1] - (-1.5 - c + drift)) < 1e-6 and abs(whi[1] - (1.5 + c)) < 1e-6, f"y {wlo[1]:.4f} .. {whi[1]:.4f}")
# -b mirrors the stream
neg = write_case("slip_neg", f"angle {alpha:g}\nsideslip {-beta:g}\n")
un = vec(read(neg, "0/U"), r"freestreamValue uniform")
expect("sideslip -b mirrors U_y", abs(un[1] + u[1]) < 1e-12 and un[0] == u[0] and un[2] == u[2], f"{un} vs {u}")
# sideslip 0: the same dictionaries as without the key
c0, c1 = write_case("zero", f"angle {alpha:g}\nsideslip 0\n"), write_case("none", f"angle {alpha:g}\n")
files = [os.path.join(d, f) for d in ("system", "0", "constant") for f in sorted(os.listdir(os.path.join(c0, d)))
         if f != "fluidSettings.json"]
same = [f for f in files if read(c0, f).replace("zero.settings", "X") == read(c1, f).replace("none.settings", "X")]
expect("sideslip 0 writes what no sideslip key writes", len(same) == len(files) and len(files) > 8,
       f"{len(same)} of {len(files)} files the same")

# The summary's lateral loads from a forces function object's output (moments about CofR, the case's axes)
import ramair_summary  # noqa: E402
base = os.path.join(case, "postProcessing", "forces", "0")
os.makedirs(base)
F, M = (3.0, -20.0, 200.0), (4.0, 1.0, -2.0)
with open(os.path.join(base, "force.dat"), "w") as f, open(os.path.join(base, "moment.dat"), "w") as g:
    for name, h, v in (("Force", f, F), ("Moment", g, M)):
        h.write(f"# {name}\n# CofR : (0 0 0)\n#\n# Time (total_x total_y total_z) (pressure_x ...)\n")
        for i in range(4):  # the first half a start-up value, the second half the settled one
            w = v if i >= 2 else (0.0, 0.0, 0.0)
            h.write(f"{0.1 * (i + 1):g}\t({w[0]:g} {w[1]:g} {w[2]:g})\t(0 0 0)\t(0 0 0)\n")
rec = json.load(open(os.path.join(case, "constant", "fluidSettings.json")))
lat = ramair_summary.lateral(case, rec["derived"])
side = lat["side_direction"]
flow = [v / speed for v in u]
expect("side direction normal to the stream and to the lift, to the right",
       abs(sum(s * w for s, w in zip(side, flow))) < 1e-8 and abs(sum(s * w for s, w in zip(side, lift))) < 1e-7
       and side[1] > 0.99, f"{side}")
qS, span = rec["derived"]["q"] * rec["derived"]["Aref"], rec["derived"]["span_projected"]
expect("side force, roll (-M_x), yaw (-M_z) over the second half, and their coefficients",
       abs(lat["side_force_N"] - sum(F[i] * side[i] for i in range(3))) < 1e-12 and lat["roll_moment_Nm"] == -4.0
       and lat["yaw_moment_Nm"] == 2.0 and abs(lat["CY"] * qS - lat["side_force_N"]) < 1e-12
       and abs(lat["Cn_yaw"] * qS * span - 2.0) < 1e-12 and abs(lat["Cl_roll"] * qS * span + 4.0) < 1e-12,
       f"side {lat['side_force_N']:.4f} N, roll {lat['roll_moment_Nm']}, yaw {lat['yaw_moment_Nm']}, span {span:g} m")

print(f"{len(bad)} failed" if bad else "all passed")
sys.exit(1 if bad else 0)
