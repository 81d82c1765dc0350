#!/usr/bin/env bash
# fsiRigidFitDisplacementLaplacian (libfsiFoam's mesh motion for a body that swings as a whole) on a 2D square
# body in a box, moved by Debian's moveDynamicMesh (no flow); the checks are rigid_fit_check.py's:
#   rigid    : a 60 deg turn about an off-centre point: the body reaches it exactly, the cells near it move
#              rigidly, the far field stays, pointDisplacement is the total displacement, checkMesh passes
#   plain    : the same turn with displacementLaplacian (inverseDistance): checkMesh fails (folded cells), which
#              is why the rigid fit exists -- and what makes the rigid case's checkMesh a discriminating check
#   deform   : a turn plus growth and translation (timeVaryingMappedFixedValue from boundaryData): the body
#              reaches it exactly, the logged fit is the prescribed rotation and translation, checkMesh passes
#   parallel : the rigid turn on 2 ranks (cut through the body): the same checks, the same fits as serial (the
#              deform motion is not run in parallel: v1912's point timeVaryingMappedFixedValue looks for its
#              boundaryData at ../constant relative to the working directory of a parallel run)
#   errors   : outerDistance reaching the far field, and coefficients under the solver's own name, are refused
#              with a message naming the patch / dictionary
# Usage: run_rigid_fit_test.sh ADAPTER_LIB WORK_DIR
set -uo pipefail
lib=$1 work=$2
here="$(cd "$(dirname "$0")" && pwd)"
python=/usr/bin/python3
export WM_PROJECT_DIR=/usr/share/openfoam
command -v moveDynamicMesh > /dev/null || { echo "moveDynamicMesh not found: skipped"; exit 77; }
rm -rf "$work" && mkdir -p "$work"
failed=0
fail() { echo "FAIL: $*"; failed=1; }

# prepare NAME: a fresh copy of the case with its mesh
prepare() {
  local dir=$work/$1
  mkdir -p "$dir" && cp -r "$here/rigid-fit/." "$dir/"
  sed -i "s|FSI_ADAPTER_LIB|$lib|" "$dir/constant/dynamicMeshDict"
  (cd "$dir" && blockMesh > log.blockMesh 2>&1) || { echo "FAIL: blockMesh in $dir"; exit 1; }
}
# deform_bc DIR: the body's displacement read from constant/boundaryData (written from its mesh)
deform_bc() {
  "$python" "$here/rigid_fit_check.py" boundary-data "$1" || fail "boundary data"
  sed -i 's|^  body {.*|  body { type timeVaryingMappedFixedValue; mapMethod nearest; value uniform (0 0 0); }|; /^         omega/d' \
    "$1/0/pointDisplacement"
}
mesh_ok() { (cd "$1" && checkMesh -latestTime > log.checkMesh 2>&1); grep -q "^Mesh OK." "$1/log.checkMesh"; }

prepare rigid
(cd "$work/rigid" && moveDynamicMesh > log.moveDynamicMesh 2>&1) || fail "rigid: moveDynamicMesh failed"
"$python" "$here/rigid_fit_check.py" rigid "$work/rigid" "$work/rigid/log.moveDynamicMesh" || fail "rigid: checks"
mesh_ok "$work/rigid" || fail "rigid: checkMesh at t = 1: $(grep -E '\*\*\*' "$work/rigid/log.checkMesh" | head -3)"

prepare plain
sed -i 's|^motionSolver .*|motionSolver displacementLaplacian;|; s|^displacementLaplacianCoeffs .*|displacementLaplacianCoeffs { diffusivity inverseDistance (body); }|' \
  "$work/plain/constant/dynamicMeshDict"
(cd "$work/plain" && moveDynamicMesh > log.moveDynamicMesh 2>&1)
if mesh_ok "$work/plain"; then fail "plain: displacementLaplacian survived the 60 deg turn; the rigid case's checkMesh proves nothing"; else
  echo "plain displacementLaplacian at 60 deg: $(grep -E 'incorrectly oriented' "$work/plain/log.checkMesh" | head -1 | sed 's/^ *//')"; fi

prepare deform
deform_bc "$work/deform"
(cd "$work/deform" && moveDynamicMesh > log.moveDynamicMesh 2>&1) || fail "deform: moveDynamicMesh failed"
"$python" "$here/rigid_fit_check.py" deform "$work/deform" "$work/deform/log.moveDynamicMesh" || fail "deform: checks"
mesh_ok "$work/deform" || fail "deform: checkMesh at t = 1"

if command -v mpirun > /dev/null; then
  prepare parallel
  printf 'FoamFile { version 2.0; format ascii; class dictionary; object decomposeParDict; }\nnumberOfSubdomains 2;\nmethod simple;\nsimpleCoeffs { n (2 1 1); delta 0.001; }\n' \
    > "$work/parallel/system/decomposeParDict"
  (cd "$work/parallel" && decomposePar > log.decomposePar 2>&1 &&
    mpirun -np 2 --allow-run-as-root --oversubscribe moveDynamicMesh -parallel > log.moveDynamicMesh 2>&1 &&
    reconstructPar -latestTime > log.reconstructPar 2>&1) || fail "parallel: decomposePar/moveDynamicMesh/reconstructPar failed"
  "$python" "$here/rigid_fit_check.py" rigid "$work/parallel" "$work/parallel/log.moveDynamicMesh" || fail "parallel: checks"
  "$python" - "$work/rigid" "$work/parallel" << 'EOF' || fail "parallel: differs from serial"
import sys
import re
serial, par = (open(f"{d}/log.moveDynamicMesh").read() for d in sys.argv[1:])
fit = lambda t: re.findall(r"rigid part: rotation (\S+) deg", t)
a, b = fit(serial), fit(par)
worst = max(abs(float(x) - float(y)) for x, y in zip(a, b))
print(f"fitted rotations serial vs 2 ranks: {len(a)} and {len(b)} updates, largest difference {worst:.3g} deg")
sys.exit(0 if len(a) == len(b) == 10 and worst < 1e-9 else 1)
EOF
fi

prepare reach
sed -i 's|outerDistance 3;|outerDistance 4;|' "$work/reach/constant/dynamicMeshDict"
(cd "$work/reach" && moveDynamicMesh > log.moveDynamicMesh 2>&1) && fail "reach: outerDistance 4 accepted"
grep -q "outerDistance 4 m reaches patch farfield" "$work/reach/log.moveDynamicMesh" || fail "reach: no message naming the far field"

prepare ownname
sed -i 's|^displacementLaplacianCoeffs|fsiRigidFitDisplacementLaplacianCoeffs|' "$work/ownname/constant/dynamicMeshDict"
(cd "$work/ownname" && moveDynamicMesh > log.moveDynamicMesh 2>&1) && fail "ownname: accepted"
grep -q "reads its coefficients" "$work/ownname/log.moveDynamicMesh" || fail "ownname: no message naming displacementLaplacianCoeffs"

[ "$failed" = 0 ] && echo "PASS"
exit "$failed"
