#!/usr/bin/env bash
# The pilot's brakes on the coupled ram-air wing (cases/coupled/ramair-kt, brake.settings: docs/RAMAIR.md) cut
# to CI size, 2 ranks, driven by a brake table (brake_table): 20 rigid steps, 30 coupled windows of inflation,
# the right toggle drawn 0.15 m down over 20 windows and held 10, then the left one drawn down as far over 20
# windows and both held 20 (a symmetric brake); remeshing on, as in brake.settings. Checks:
#   run          all 100 windows, each once; force fluid = structure (< 1e-6) in every window; at least one new
#                mesh during the pull (the moved design mesh cannot follow the trailing edge drawn down: without
#                remeshing the mesh guard stops every such run), each new mesh passing checkMesh
#   right brake  the signs a pilot expects, from the flow's load on the mirror-symmetric wing about the anchor:
#                before the pull no yaw or roll (below 5 % of what the held brake gives); the right brake held, a
#                yaw moment that turns the nose to the right (a right turn) and a roll moment that lifts the
#                braked right wing (its deflected trailing edge adds lift and drag on that side); the right brake
#                lines carry the pull (more than 3x the left ones)
#   both brakes  held symmetric: the turn gone (yaw below 30 % of the right brake's) and the centre section's
#                angle of attack above that of the same 100 windows run without brakes (the trailing edge drawn
#                down); the lift and drag against the unbraked run's are reported (on this wall treatment the
#                braked canopy flies past the angle where the bulged wing loses lift: docs/RAMAIR.md)
#   outputs      summary.md has the brakes' rows and asks for no turn; plots/brake.png exists and is not blank
# Exit 77 (ctest: skipped) without Debian's OpenFOAM binaries.
# Usage: run_ramair_brake_test.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -uo pipefail
src=$1 build=$2 work=$3
. "$(dirname "$0")/ramair_test_case.sh"

# windows of 8.337 ms: the right pull in windows 30-50, held to 60, the left pull 60-80, both held to 100
printf '%s\n' "time,left,right" "0,0,0" "0.2501,0,0" "0.41685,0,0.15" "0.5002,0,0.15" "0.66696,0.15,0.15" > brakes.csv
sed -e 's/^steps .*/steps 100/' -e 's/^rigid_steps .*/rigid_steps 20/' -e 's/^carry_after .*/carry_after 20/' \
  -e '/^brake_right /d' -e '/^brake_start /d' -e '/^brake_duration /d' \
  -e 's/^write_interval .*/write_interval 5/' brake.settings > short.settings
echo "brake_table brakes.csv" >> short.settings
grep -q '^remesh_below' short.settings || fail "brake.settings has no remesh_below"
start=$(date +%s)
./Allrun.parallel -settings short.settings > ../brake.log 2>&1 || { tail -30 ../brake.log; fail "Allrun.parallel failed"; }
echo "Allrun.parallel: $(($(date +%s) - start)) s"
grep "New mesh\|brakes left" ../brake.log
# the same 100 windows without brakes (the inflation from rest is still going on: the symmetric brake's
# effect is the difference between the two runs at the same time, not a before and after)
mkdir -p ../plain && for f in $case_files; do cp "$src/$f" ../plain/; done
grep -v '^brake_table' short.settings > ../plain/short.settings
(cd ../plain && ./Allrun.parallel -settings short.settings > ../plain.log 2>&1) || { tail -30 ../plain.log; fail "the unbraked run failed"; }

/usr/bin/python3 - <<'PY'
import json, os, struct, sys
s = json.load(open("summary.json"))
c = s["coupled"]
bad = []
def check(ok, what):
    if not ok:
        bad.append(what)
check(c["windows"] == 100, f"{c['windows']} windows, not 100")
times = c["history"]["time"]
check(len(set(round(t, 9) for t in times)) == len(times), "a window ran twice")
check(c["force_fluid_vs_structure_max_relative"] < 1e-6, "fluid and structure interface forces differ by 1e-6 or more")
meshes = s.get("remeshes", [])
check(len(meshes) >= 1, "no new mesh during the pull")
for i, m in enumerate(meshes, 1):
    mesh = m.get("mesh", {})
    check(mesh.get("ok") or mesh.get("only_skewness"), f"new mesh {i} fails checkMesh: {mesh.get('failed_checks')}")
import csv
with open("structure/coupling.csv") as f:
    rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
dt = float(rows[1]["time"]) - float(rows[0]["time"])
def mean(w0, w1, rows=rows):
    part = [r for r in rows if w0 * dt - 1e-9 <= float(r["time"]) <= w1 * dt + 1e-9]
    keys = {"yaw": lambda r: -float(r["anchor_moment_z"]), "roll": lambda r: -float(r["anchor_moment_x"]),
            "lift": lambda r: float(r["Fz_fluid"]), "drag": lambda r: float(r["Fx_fluid"]),
            "brake_right": lambda r: float(r["brake_tension_right"]), "brake_left": lambda r: float(r["brake_tension_left"])}
    return {k: sum(f(r) for r in part) / len(part) for k, f in keys.items()} if part else None
p, h, both = mean(21, 30), mean(53, 60), mean(88, 100)
with open("../plain/structure/coupling.csv") as f:
    rows_plain = list(csv.DictReader(line for line in f if not line.startswith("#")))
unbraked = mean(88, 100, rows_plain)
check(p is not None and h is not None and both is not None, "windows missing")
if p and h and both:
    print(f"before: yaw {p['yaw']:.4f} N m, roll {p['roll']:.4f}, lift {p['lift']:.1f} N, drag {p['drag']:.2f} N")
    print(f"right held: yaw {h['yaw']:.3f} N m, roll {h['roll']:.3f}, brake lines {h['brake_right']:.1f} / {h['brake_left']:.1f} N")
    print(f"both held: yaw {both['yaw']:.3f} N m, roll {both['roll']:.3f}, lift {both['lift']:.1f} N, drag {both['drag']:.2f} N")
    check(h["yaw"] < 0, f"right brake held: yaw {h['yaw']:.3f} N m: not a right turn")
    check(h["roll"] > 0, f"right brake held: roll {h['roll']:.3f} N m: the braked right wing is not lifted")
    check(abs(p["yaw"]) < 0.05 * abs(h["yaw"]) and abs(p["roll"]) < 0.05 * abs(h["roll"]),
          "yaw or roll before the pull on the symmetric wing")
    check(h["brake_right"] > 3 * h["brake_left"], "the right brake lines do not carry the pull")
    check(abs(both["yaw"]) < 0.3 * abs(h["yaw"]), f"both brakes held: yaw {both['yaw']:.3f} N m, the turn not gone")
    # Reported, not asserted: a parafoil's symmetric brake raises CL and CD, but on this mesh's wall treatment
    # the bulged canopy loses lift above about 4 deg of inflow (docs/AERODYNAMICS.md rungs 2 and 3), and the
    # braked centre section flies at about 9 deg: measured 112 N of lift against the unbraked 204 N
    # (2026-11-29). The wall-resolved canopy does not trim yet, so the expected rise cannot be shown here.
    print(f"unbraked at the same windows: lift {unbraked['lift']:.1f} N, drag {unbraked['drag']:.2f} N "
          "(the symmetric brake's lift and drag against these: reported, docs/RAMAIR.md)")
alpha = s["wing"]["section_alpha"]["centre_deg"]
alpha_plain = json.load(open("../plain/summary.json"))["wing"]["section_alpha"]["centre_deg"]
print(f"centre section's angle at the end: {alpha:.2f} deg braked, {alpha_plain:.2f} deg unbraked")
check(alpha > alpha_plain, f"both brakes held: the centre section's angle {alpha:.2f} deg is not above the "
      f"unbraked wing's {alpha_plain:.2f} deg")
b = c.get("brake")
check(b is not None and b.get("turn_asked") == "none", "summary.json: the symmetric brake does not ask for no turn")
md = open("summary.md").read()
check("brakes held" in md, "summary.md has no brake rows")
png = "plots/brake.png"
if not os.path.exists(png):
    bad.append("no plots/brake.png")
else:
    head = open(png, "rb").read(32)
    check(head[:8] == b"\x89PNG\r\n\x1a\n", "plots/brake.png is not a PNG")
    w, hgt = struct.unpack(">II", head[16:24])
    check(w > 300 and hgt > 300 and os.path.getsize(png) > 20000, "plots/brake.png is blank or tiny")
if bad:
    print("FAIL: " + "; ".join(bad))
    sys.exit(1)
print("PASS brake")
PY
