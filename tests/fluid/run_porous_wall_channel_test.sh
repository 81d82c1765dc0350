#!/usr/bin/env bash
# ctest fluid.porous-wall-channel: cases/fluid/porous-wall-channel copied out of the source tree and run by its
# Allrun (four speeds and a moving cloth): the drop across the adapter's permeable wall pair (fsiPorousWall) is
# the Darcy-Forchheimer law at the measured through-flow, the through-flow is the inflow (minus the wall's speed
# when it moves), the two sides' fluxes cancel, a and b fitted back are the inputs (the case's own checks, exit
# 1 naming a failure). Then: one side's faces reversed in the mesh (paired by nearest centre), the two sides on
# different processors (gathered), and the located errors: a partner patch with another face count, a partner
# that is no patch, a partner whose faces are elsewhere. Exit 77 (skipped) without Debian's OpenFOAM or the
# adapter library.
# Usage: run_porous_wall_channel_test.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -u
src=$1/cases/fluid/porous-wall-channel
export FSI_LIB_DIR=$2/lib
work=$3
fail() { echo "FAIL: $*" >&2; exit 1; }
command -v pimpleFoam > /dev/null && command -v createBaffles > /dev/null || { echo "no OpenFOAM: skipped"; exit 77; }
[ -f "$FSI_LIB_DIR/libfsiFoam.so" ] || { echo "no $FSI_LIB_DIR/libfsiFoam.so (adapter not built): skipped"; exit 77; }
rm -rf "$work" && mkdir -p "$(dirname "$work")" && cp -r "$src" "$work" || fail "copying the case"
"$work/Allrun" || fail "Allrun failed (its checks above)"
for f in summary.json porous_wall_channel.png log.Allrun runs/u_0.5/u_0.5.foam runs/moving_u_0.5/moving_u_0.5.foam; do
  [ -e "$work/$f" ] || fail "Allrun did not write $f"
done
/usr/bin/python3 - "$work/summary.json" <<'PY' || fail "summary.json"
import json, sys
s = json.load(open(sys.argv[1]))
assert not s["failures"], s["failures"]
assert len(s["points"]) == 4, "four speeds"
m = s["moving"]
assert m and m["wall_speed"] > 0, "the moving run"
# the wall's motion is a tenth of the through-flow: dropping it would move the inflow by that much
assert abs(m["inflow"] - m["wall_speed"] - m["through_flow"]) < 1e-3 * m["through_flow"], m
assert all(p["pair_imbalance"] <= 1e-9 for p in s["points"] + [m]), "fluxes through the two sides"
PY
# the partner's faces in another order (cloth_down's faces reversed in the mesh files): the condition pairs
# them by nearest centre (it says so), and the run still follows the law and conserves mass
run=$work/runs/u_0.25
rm -rf "$run"/[1-9]* "$run/postProcessing"
/usr/bin/python3 - "$run/constant/polyMesh" <<'PY' || fail "reversing cloth_down's faces"
import re, sys
mesh = sys.argv[1]
start, n = [int(x) for x in re.search(r"cloth_down\s*\{[^}]*?nFaces\s+(\d+);\s*startFace\s+(\d+);",
                                      open(mesh + "/boundary").read()).groups()[::-1]]
for name in ("faces", "owner"):
    lines = open(f"{mesh}/{name}").read().split("\n")
    first = lines.index("(") + 1
    lines[first + start:first + start + n] = lines[first + start:first + start + n][::-1]
    open(f"{mesh}/{name}", "w").write("\n".join(lines))
PY
(cd "$run" && WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam} LD_LIBRARY_PATH=$FSI_LIB_DIR:${LD_LIBRARY_PATH:-} \
  pimpleFoam > log.reversed 2>&1) || fail "pimpleFoam on the reversed faces: $run/log.reversed"
grep -q "cloth_down: faces paired with cloth_up by nearest centre" "$run/log.reversed" ||
  fail "the reversed faces were not paired by nearest centre"
/usr/bin/python3 - "$run" "$work/summary.json" <<'PY' || fail "the reversed faces' run"
import json, sys
run, s = sys.argv[1], json.load(open(sys.argv[2]))
last = lambda f: [float(w) for w in open(f).read().strip().split("\n")[-1].split()]
p = last(run + "/postProcessing/plenums/0/p")
up = last(run + "/postProcessing/throughFlow/0/surfaceFieldValue.dat")[1]
down = last(run + "/postProcessing/throughFlowDown/0/surfaceFieldValue.dat")[1]
u, drop = up / 0.1, p[1] - p[2]
law = s["a_per_m"] * s["nu"] * u + s["b"] * u * u
assert abs(drop / law - 1) < s["tolerance"], (drop, law)
assert abs(up + down) <= 1e-9 * abs(up), (up, down)
print(f"reversed faces: through-flow {u:.6g} m/s, drop {drop:.6g}, law {law:.6g} (kinematic)")
PY
# in parallel with the cloth's two sides on different processors (simple decomposition 2 x 1 at x = 0: the
# upstream cells and cloth_up on one, the downstream cells and cloth_down on the other): the partner's faces
# and pressures come from the other processor; the run still follows the law and conserves mass
if command -v mpirun > /dev/null && command -v decomposePar > /dev/null; then
  run=$work/runs/u_1
  rm -rf "$run"/[1-9]* "$run/postProcessing" "$run"/processor*
  printf 'FoamFile { version 2.0; format ascii; class dictionary; object decomposeParDict; }\nnumberOfSubdomains 2;\nmethod simple;\ncoeffs { n (2 1 1); }\n' > "$run/system/decomposeParDict"
  mpi=(mpirun -np 2)
  mpirun --version 2> /dev/null | grep -q "Open MPI" && mpi+=(--allow-run-as-root --oversubscribe)
  (cd "$run" && export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam} LD_LIBRARY_PATH=$FSI_LIB_DIR:${LD_LIBRARY_PATH:-} &&
    decomposePar > log.decomposePar 2>&1 && "${mpi[@]}" pimpleFoam -parallel > log.parallel 2>&1) ||
    fail "the parallel run: $run/log.parallel"
  /usr/bin/python3 - "$run" "$work/summary.json" <<'PY' || fail "the parallel run's numbers"
import glob, json, sys
run, s = sys.argv[1], json.load(open(sys.argv[2]))
sizes = {}
for d in glob.glob(run + "/processor*/constant/polyMesh/boundary"):
    t = open(d).read()
    for name in ("cloth_up", "cloth_down"):
        i = t.index(name + "\n")
        sizes[(d.split("/")[-4], name)] = int(t[t.index("nFaces", i):].split()[1].rstrip(";"))
# each processor holds one side only
assert sorted(sizes.values()) == [0, 0, 4, 4] and sizes[("processor0", "cloth_up")] != sizes[("processor1", "cloth_up")], sizes
last = lambda f: [float(w) for w in open(f).read().strip().split("\n")[-1].split()]
p = last(run + "/postProcessing/plenums/0/p")
up = last(run + "/postProcessing/throughFlow/0/surfaceFieldValue.dat")[1]
down = last(run + "/postProcessing/throughFlowDown/0/surfaceFieldValue.dat")[1]
u, drop = up / 0.1, p[1] - p[2]
serial = [q for q in s["points"] if q["name"] == "u_1"][0]
law = s["a_per_m"] * s["nu"] * u + s["b"] * u * u
assert abs(drop / law - 1) < s["tolerance"], (drop, law)
assert abs(up + down) <= 1e-9 * abs(up), (up, down)
assert abs(u / serial["through_flow"] - 1) < 1e-6, (u, serial["through_flow"])
print(f"parallel, the sides apart: through-flow {u:.9g} m/s (serial {serial['through_flow']:.9g}), drop {drop:.6g}, law {law:.6g}")
PY
else
  echo "no mpirun/decomposePar: the parallel check skipped"
fi
# located errors: the run's field file names the entry (file and line) and what is wrong
run=$work/runs/u_0.5
expect_error() {  # $1: sed edit of 0/U, $2: text the error must contain
  cp "$run/0/U" "$run/U.good"
  sed -i "$1" "$run/0/U"
  cmp -s "$run/0/U" "$run/U.good" && fail "the edit $1 changed nothing"
  (cd "$run" && WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam} LD_LIBRARY_PATH=$FSI_LIB_DIR:${LD_LIBRARY_PATH:-} \
    pimpleFoam > log.error 2>&1) && fail "pimpleFoam accepted: $1"
  grep -q "$2" "$run/log.error" || { tail -20 "$run/log.error"; fail "no '$2' in the error of: $1"; }
  grep -q "0/U.* line [0-9]" "$run/log.error" || { tail -20 "$run/log.error"; fail "the error of $1 names no file and line"; }
  mv "$run/U.good" "$run/0/U"
}
rm -rf "$run"/[1-9]*
expect_error "0,/partner *cloth_down;/s//partner sides;/" "80 faces but partner\|has 80"
expect_error "0,/partner *cloth_down;/s//partner nowhere;/" "'nowhere' is not a patch"
expect_error "0,/partner *cloth_down;/s//partner inlet;/" "has no face of inlet"
"$work/Allclean" && [ ! -e "$work/runs" ] || fail "Allclean left runs/"
echo "fluid.porous-wall-channel: passed"
