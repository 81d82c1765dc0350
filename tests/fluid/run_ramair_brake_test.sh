#!/usr/bin/env bash
# The right brake pulled on the coupled ram-air wing (cases/coupled/ramair-kt, brake.settings: docs/RAMAIR.md
# "ramair-brake") cut to CI size, 2 ranks: 20 rigid steps, 30 coupled windows of inflation, the right toggle
# drawn 0.25 m down over 20 windows (a pull three times as fast as brake.settings'), 20 windows held; remeshing
# on, as in brake.settings. Checks:
#   run          all 70 windows, each once; force fluid = structure (< 1e-6) in every window; at least one new
#                mesh during the pull (the moved design mesh cannot follow the trailing edge drawn down: without
#                remeshing the mesh guard stops every such run), each new mesh passing checkMesh
#   brake        the signs a pilot expects, from the flow's load on the mirror-symmetric wing about the anchor:
#                before the pull no yaw or roll (below 5 % of what the held brake gives); held, a yaw moment that
#                turns the nose to the right (a right turn) and a roll moment that lifts the braked right wing
#                (its deflected trailing edge adds lift and drag on that side); the right brake lines carry
#                the pull (more than 3x the left ones)
#   outputs      summary.md has the brake's rows; plots/brake.png exists and is not blank
# Exit 77 (ctest: skipped) without Debian's OpenFOAM binaries.
# Usage: run_ramair_brake_test.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -uo pipefail
src=$1 build=$2 work=$3
. "$(dirname "$0")/ramair_test_case.sh"

# windows of 8.337 ms: the pull from window 30 to 50
sed -e 's/^steps .*/steps 70/' -e 's/^rigid_steps .*/rigid_steps 20/' -e 's/^carry_after .*/carry_after 20/' \
  -e 's/^brake_start .*/brake_start 0.25/' -e 's/^brake_duration .*/brake_duration 0.1667/' \
  -e 's/^write_interval .*/write_interval 10/' brake.settings > short.settings
grep -q '^remesh_below' short.settings || fail "brake.settings has no remesh_below"
start=$(date +%s)
./Allrun.parallel -settings short.settings > ../brake.log 2>&1 || { tail -30 ../brake.log; fail "Allrun.parallel failed"; }
echo "Allrun.parallel: $(($(date +%s) - start)) s"
grep "New mesh\|brakes left" ../brake.log

/usr/bin/python3 - <<'PY'
import json, os, struct, sys
s = json.load(open("summary.json"))
c = s["coupled"]
bad = []
def check(ok, what):
    if not ok:
        bad.append(what)
check(c["windows"] == 70, f"{c['windows']} windows, not 70")
times = c["history"]["time"]
check(len(set(round(t, 9) for t in times)) == len(times), "a window ran twice")
check(c["force_fluid_vs_structure_max_relative"] < 1e-6, "fluid and structure interface forces differ by 1e-6 or more")
meshes = s.get("remeshes", [])
check(len(meshes) >= 1, "no new mesh during the pull")
for i, m in enumerate(meshes, 1):
    mesh = m.get("mesh", {})
    check(mesh.get("ok") or mesh.get("only_skewness"), f"new mesh {i} fails checkMesh: {mesh.get('failed_checks')}")
b = c.get("brake")
check(b is not None and b.get("held"), "summary.json has no held brake")
if b and b.get("held"):
    h, p = b["held"], b["before"]
    print(f"held: yaw {h['yaw_Nm']:.3f} N m, roll {h['roll_Nm']:.3f} N m, side {h['side_N']:.2f} N, brake lines "
          f"{h['brake_right_N']:.1f} / {h['brake_left_N']:.1f} N; before: yaw {p['yaw_Nm']:.4f}, roll {p['roll_Nm']:.4f}")
    check(h["yaw_Nm"] < 0, f"held yaw {h['yaw_Nm']:.3f} N m: not a right turn")
    check(h["roll_Nm"] > 0, f"held roll {h['roll_Nm']:.3f} N m: the braked right wing is not lifted")
    check(abs(p["yaw_Nm"]) < 0.05 * abs(h["yaw_Nm"]) and abs(p["roll_Nm"]) < 0.05 * abs(h["roll_Nm"]),
          "yaw or roll before the pull on the symmetric wing")
    check(h["brake_right_N"] > 3 * h["brake_left_N"], "the right brake lines do not carry the pull")
    check(b["right_turn"], "summary.json: right_turn false")
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
