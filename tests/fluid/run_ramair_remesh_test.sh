#!/usr/bin/env bash
# Remeshing during a coupled run (`remesh_below`, docs/COUPLING.md "Remeshing during a run") on the main job's
# wing (cases/coupled/ramair-kt, coupled.settings) cut to 20 rigid steps and 6 coupled windows, 2 ranks. Three
# runs: `plain` without remeshing; `remesh` with remesh_below 0.95, so that the run stops for a new mesh every
# window or two; `same-mesh`, which continues `remesh` from its first stop on a "new" mesh that is the old one
# as the run left it, with the flow copied field by field. Checks:
#   bookkeeping  same-mesh continues the run as if there were no new mesh: lift within 0.5 % and drag within
#                5 % of plain's in every window. Snapping and field mapping are left out, so what is tested is
#                the adapter's account of which structure displacement the new mesh's undeformed skin stands for
#                (interfaceReference restart, remesh_reference). Taking the structure's state instead of the
#                displacement the fluid had moves the wall by a window's prediction error: 7 % more lift in the
#                first window.
#   remeshing    remesh runs all 6 windows, each once, at the same times as plain; at least 2 new meshes, each
#                with checkMesh passing (skewness excepted, as for the first mesh) and its skin written; force
#                fluid = structure (< 1e-6) in every window; summary.json lists the new meshes; each earlier
#                mesh's case stays in stageN/ with a .foam file.
#   reported     remesh's lift and drag against plain's at the end (the snapped and mapped flow's transient,
#                docs/COUPLING.md).
#   capped       `capped` is remesh with remesh_max 1: Allrun stops when the run asks for a second new mesh,
#                exit non-zero, a message naming remesh_max and the time, the case kept as the run left it
#                (the request, the fields at that time on both ranks, stage1/ and no stage2/).
#   stopped      plain interrupted by SIGINT after 2 coupled windows (exit 130, fields and structure state at the
#                stop on both ranks) and continued by `./Allrun -continue`: plain's 6 windows, lift within 0.5 %
#                and drag within 5 % of plain's in each (issue 35 item 5)
#   wall         `wall` is plain with wall_layers 3 and wall_after 3 (the adapter's remeshAt): 3 windows on the
#                plain mesh, one new mesh at t = 3 dt with prism layers on the wing (snappyHexMeshDict.wall; more
#                cells than the first mesh, checkMesh passing), then the last 3 steps' flow time in 12 windows of
#                dt/4 with a quarter of the equilibrium pseudo-steps, to plain's end time, force fluid = structure
#                in every window.
# Exit 77 (ctest: skipped) without Debian's OpenFOAM binaries.
# Usage: run_ramair_remesh_test.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -uo pipefail
src=$1 build=$2 work=$3
. "$(dirname "$0")/ramair_test_case.sh"

sed -e 's/^steps .*/steps 6/' -e 's/^rigid_steps .*/rigid_steps 20/' -e 's/^carry_after .*/carry_after 20/' \
  -e 's/^write_interval .*/write_interval 1/' coupled.settings > short.settings
cd .. || exit 1
cp -r ramair-kt plain && cp -r ramair-kt remesh && cp -r ramair-kt capped && cp -r ramair-kt wall || fail "copying the case"
printf 'wall_layers 3\nwall_after 3\n' >> wall/short.settings
echo "remesh_below 0.95" >> remesh/short.settings
printf 'remesh_below 0.95\nremesh_max 1\n' >> capped/short.settings
(cd plain && ./Allrun.parallel -settings short.settings > ../plain.log 2>&1) || { tail -20 plain.log; fail "plain: Allrun failed"; }
(cd remesh && ./Allrun.parallel -settings short.settings > ../remesh.log 2>&1) || { tail -20 remesh.log; fail "remesh: Allrun failed"; }
grep "New mesh" remesh.log

(cd capped && ./Allrun.parallel -settings short.settings > ../capped.log 2>&1) && fail "capped: Allrun went on past remesh_max 1"
grep -q "remesh_max 1 reached: 1 new meshes since t = " capped.log || { tail -5 capped.log; fail "capped: no remesh_max message"; }
Tc=$(sed -n 's/^time //p' capped/structure/remesh/request 2>/dev/null)
[ -n "$Tc" ] || fail "capped: the second request is gone"
grep -q "asks for another at t = $Tc s" capped.log || fail "capped: the message does not name t = $Tc"
for r in 0 1; do [ -f "capped/processor$r/$Tc/U" ] || fail "capped: no fields at $Tc on rank $r"; done
[ -d capped/stage1 ] && [ ! -d capped/stage2 ] || fail "capped: expected stage1/ and no stage2/"
echo "capped: stopped at t = $Tc as asked"

(cd wall && ./Allrun.parallel -settings short.settings > ../wall.log 2>&1) || { tail -20 wall.log; fail "wall: Allrun failed"; }
grep -E "New mesh|Thin wall cells" wall.log
grep -q "Layers added" wall/log.snappyHexMesh.remesh1 && ! grep -q "Layers added" wall/log.snappyHexMesh ||
  fail "wall: the first mesh should have no layers and the new one should (log.snappyHexMesh, .remesh1)"
[ -d wall/stage1 ] && [ ! -d wall/stage2 ] || fail "wall: expected one new mesh (stage1/, no stage2/)"

# stopped: plain interrupted by SIGINT after its second coupled window (Allrun exits 130 with the state written at
# the window's end on both ranks), then `./Allrun -continue` (the settings and -parallel recorded) to the end
mkdir -p stopped && cp -r ramair-kt/. stopped/ && rm -f stopped/*.log
cd stopped || exit 1
set -m
./Allrun.parallel -settings short.settings > ../stopped.log 2>&1 &
pid=$!
set +m
n=0
until [ "$(grep -vc '^[#t]' structure/coupling.csv 2> /dev/null || true)" -ge 2 ] 2> /dev/null; do
  sleep 0.2
  n=$((n + 1))
  kill -0 $pid 2> /dev/null && [ $n -lt 3000 ] || { tail -20 ../stopped.log; fail "stopped: no second window"; }
done
kill -INT $pid
wait $pid
rc=$?
[ $rc -eq 130 ] || { tail -20 ../stopped.log; fail "stopped: Allrun exited $rc on SIGINT, not 130"; }
Ts=$(sed -n 's/^time //p' structure/interrupted)
for r in 0 1; do
  [ -f "processor$r/$Ts/U" ] || fail "stopped: no fields at $Ts on rank $r"
done
[ -f "processor0/$Ts/uniform/fsiStructure.h5" ] || fail "stopped: no structure state at $Ts"
grep -q "^Allrun: stopped on SIGINT at t = $Ts s.* ./Allrun -continue" ../stopped.log || fail "stopped: no line naming ./Allrun -continue"
./Allrun -continue > ../continued.log 2>&1 || { tail -20 ../continued.log; fail "stopped: ./Allrun -continue failed"; }
grep -q "continued from t = $Ts" ../continued.log || fail "stopped: the continued run did not start at $Ts"
[ -f summary.json ] || fail "stopped: no summary.json after -continue"
cd .. || exit 1
echo "stopped: SIGINT at t = $Ts, continued to the end"

# same-mesh: remesh's first stop, continued on the old mesh as moved (stage1/T/polyMesh/points as the new
# undeformed points), its fields copied (U p k omega nut and the fluxes phi, Uf), the displacement zero.
T=$(sed -n 's/^time //p' remesh/structure/remesh.1/request)
[ -n "$T" ] && [ -d "remesh/stage1/$T" ] || fail "remesh: no first stop in stage1/"
mkdir -p same-mesh/constant "same-mesh/$T"
cp -r remesh/stage1/system same-mesh/
for f in remesh/stage1/constant/*; do [ -f "$f" ] && cp "$f" same-mesh/constant/; done
cp -r remesh/stage1/constant/polyMesh same-mesh/constant/
cp "remesh/stage1/$T/polyMesh/points" same-mesh/constant/polyMesh/points
for f in U p k omega nut phi Uf; do cp "remesh/stage1/$T/$f" "same-mesh/$T/" || fail "same-mesh: no $f at $T"; done
cp -r "remesh/stage1/$T/uniform" "same-mesh/$T/"
cp remesh/structure-coupled.yaml remesh/structure.yaml same-mesh/
cp -r remesh/structure same-mesh/structure && rm -rf same-mesh/structure/remesh.*
(
  cd same-mesh || exit 1
  /usr/bin/python3 "$build/share/fsi/ramair_fluid.py" fields . && cp 0/pointDisplacement "$T/" && rm -rf 0 || exit 1
  foamDictionary -entry functions/fsi/interfaceReference -set restart system/controlDict > /dev/null || exit 1
  foamDictionary -entry functions/fsi/remeshBelow -set 0 system/controlDict > /dev/null || exit 1
  decomposePar > log.decomposePar 2>&1 || exit 1
  mpirun -np 2 pimpleFoam -parallel > log.pimpleFoam 2>&1
) || { tail -20 same-mesh/log.pimpleFoam; fail "same-mesh: the continued run failed"; }

/usr/bin/python3 - <<'PY'
import csv, json, os, sys
bad = []
def check(ok, what):
    if not ok:
        bad.append(what)
def rows(case):
    with open(os.path.join(case, "structure", "coupling.csv")) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))
plain, remesh, same = rows("plain"), rows("remesh"), rows("same-mesh")
check(len(plain) == 6, f"plain: {len(plain)} windows, not 6")
check(len(remesh) == 6, f"remesh: {len(remesh)} windows, not 6 (each once)")
for a, b in zip(plain, remesh):
    check(abs(float(a["time"]) - float(b["time"])) < 1e-6, f"remesh: window at t = {b['time']}, plain's at {a['time']}")
for r in remesh:
    f = [float(r[k]) for k in ("Fx_fluid", "Fy_fluid", "Fz_fluid")]
    g = [float(r[k]) for k in ("Fx_structure", "Fy_structure", "Fz_structure")]
    check(max(abs(x - y) for x, y in zip(f, g)) < 1e-6 * max(abs(x) for x in f), f"remesh: force fluid != structure at {r['time']}")
with open(os.path.join("remesh", "structure", "remesh.1", "request")) as f:
    t_stop = float(next(line.split()[1] for line in f if line.startswith("time ")))
by_time = {round(float(r["time"]), 6): r for r in plain}
n = 0
for r in same:
    a = by_time.get(round(float(r["time"]), 6))
    if a is None or float(r["time"]) <= t_stop * (1 + 1e-9):
        continue  # the windows before the stop are the remesh run's own
    lift, drag = (float(r["Fz_fluid"]), float(a["Fz_fluid"])), (float(r["Fx_fluid"]), float(a["Fx_fluid"]))
    dl, dd = abs(lift[0] / lift[1] - 1), abs(drag[0] / drag[1] - 1)
    print(f"t {r['time']}: lift {lift[0]:.3f} (plain {lift[1]:.3f}, {100 * dl:.2f} %), drag {drag[0]:.3f} "
          f"(plain {drag[1]:.3f}, {100 * dd:.2f} %)")
    n += 1
    check(dl < 0.005, f"same-mesh: lift {100 * dl:.2f} % off plain's at t = {r['time']}")
    check(dd < 0.05, f"same-mesh: drag {100 * dd:.2f} % off plain's at t = {r['time']}")
check(n >= 3, f"same-mesh: {n} windows to compare, fewer than 3")
# stopped + continued: plain's windows, the ones after the stop within the same-mesh bounds (the restart continues
# fields written with 12 digits and the structure's state exactly)
stopped = rows("stopped")
check(len(stopped) == 6, f"stopped: {len(stopped)} windows after -continue, not 6")
for r, a in zip(stopped, plain):
    lift, drag = (float(r["Fz_fluid"]), float(a["Fz_fluid"])), (float(r["Fx_fluid"]), float(a["Fx_fluid"]))
    dl, dd = abs(lift[0] / lift[1] - 1), abs(drag[0] / drag[1] - 1)
    print(f"stopped t {r['time']}: lift {lift[0]:.3f} (plain {lift[1]:.3f}, {100 * dl:.3f} %), drag {100 * dd:.3f} % off")
    check(abs(float(r["time"]) - float(a["time"])) < 1e-6, f"stopped: window at {r['time']}, plain's at {a['time']}")
    check(dl < 0.005 and dd < 0.05, f"stopped: lift {100 * dl:.2f} % / drag {100 * dd:.2f} % off plain's at t = {r['time']}")
wall = rows("wall")
dt = float(plain[1]["time"]) - float(plain[0]["time"])
times = [float(r["time"]) for r in wall]
check(len(wall) == 15, f"wall: {len(wall)} windows, not 3 + 12")
if len(wall) == 15:
    check(all(abs(times[i] - float(plain[i]["time"])) < 1e-6 for i in range(3)), "wall: the first 3 windows are not plain's")
    steps = [b - a for a, b in zip(times[3:], times[4:])]
    check(all(abs(x - dt / 4) < 1e-6 * dt for x in steps), f"wall: the windows after the new mesh are not dt/4: {steps}")
    check(abs(times[-1] - float(plain[-1]["time"])) < 1e-6, f"wall: ends at {times[-1]}, plain at {plain[-1]['time']}")
for r in wall:
    f = [float(r[k]) for k in ("Fx_fluid", "Fy_fluid", "Fz_fluid")]
    g = [float(r[k]) for k in ("Fx_structure", "Fy_structure", "Fz_structure")]
    check(max(abs(x - y) for x, y in zip(f, g)) < 1e-6 * max(abs(x) for x in f), f"wall: force fluid != structure at {r['time']}")
with open(os.path.join("wall", "structure", "remesh.1", "request")) as f:
    req = f.read()
check("reason remeshAt" in req, f"wall: the new mesh was not asked for by remeshAt: {req!r}")
sj = json.load(open(os.path.join("wall", "summary.json")))
cells0 = json.load(open(os.path.join("plain", "summary.json")))["mesh"]["cells"]
sr = sj.get("remeshes", [])
check(len(sr) == 1, f"wall: {len(sr)} new meshes in summary.json, not 1")
cells1 = sr[0]["mesh"]["cells"] if sr else 0
check(cells1 > 1.1 * cells0, f"wall: {cells1} cells on the new mesh, plain {cells0}: no layers")
check(bool(sr) and (sr[0]["mesh"]["ok"] or sr[0]["mesh"]["only_skewness"]), "wall: checkMesh fails on the new mesh")
with open(os.path.join("wall", "system", "controlDict")) as f:
    cd = f.read()
check("equilibriumSteps 50;" in cd, "wall: controlDict's equilibriumSteps is not 200 / 4")
print(f"wall: {len(wall)} windows, {cells1} cells on the new mesh (plain {cells0}); lift at the end "
      f"{float(wall[-1]['Fz_fluid']):.2f} N (plain {float(plain[-1]['Fz_fluid']):.2f})")
s = json.load(open(os.path.join("remesh", "summary.json")))
rm = s.get("remeshes", [])
check(len(rm) >= 2, f"remesh: {len(rm)} new meshes, not at least 2")
for i, r in enumerate(rm, 1):
    m = r.get("mesh", {})
    check(m.get("ok") or m.get("only_skewness"), f"new mesh {i}: checkMesh fails {m.get('failed')}")
    check(os.path.getsize(os.path.join("remesh", "structure", f"remesh.{i}", "wing.stl")) > 1000, f"new mesh {i}: no skin")
    check(os.path.exists(os.path.join("remesh", f"stage{i}", f"stage{i}.foam")), f"stage{i}/ has no .foam file")
a, b = plain[-1], remesh[-1]
print(f"remesh at the end: lift {float(b['Fz_fluid']):.2f} N (plain {float(a['Fz_fluid']):.2f}), drag "
      f"{float(b['Fx_fluid']):.2f} N (plain {float(a['Fx_fluid']):.2f}); {len(rm)} new meshes")
for x in bad:
    print("FAIL:", x)
sys.exit(1 if bad else 0)
PY
rc=$?
[ $rc -eq 0 ] && echo "PASS ramair-kt remesh" || echo "FAIL ramair-kt remesh"
exit $rc
