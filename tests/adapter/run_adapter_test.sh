#!/usr/bin/env bash
# Runs the tiny cavity case with Debian's pimpleFoam and the fsiFoam function object, in one of the modes:
#   forces      : runs; the interface pressure force equals OpenFOAM's own `forces` function object (1e-6)
#   wrong-patch : a misspelt patch name stops the solver with a non-zero exit and names the patch
#   bad-scene   : a missing structure scene stops the solver with a non-zero exit and names the file
#   moving      : moving-mesh case (interface pointDisplacement of type fsiInterfaceDisplacement) runs
#   missing-library : the same case without the library is a hard error naming the boundary condition
# Usage: run_adapter_test.sh MODE ADAPTER_LIB WORK_DIR
set -uo pipefail
mode=$1 lib=$2 work=$3
here="$(cd "$(dirname "$0")" && pwd)"
export WM_PROJECT_DIR=/usr/share/openfoam
case_dir=cavity
case "$mode" in moving|missing-library) case_dir=cavity-moving ;; esac
rm -rf "$work" && mkdir -p "$work" && cp -r "$here/$case_dir/." "$work/" && cd "$work"
sed -i "s|FSI_ADAPTER_LIB|$lib|" system/controlDict
case "$mode" in
  wrong-patch) sed -i 's/fsiCoupling; libs ("\([^"]*\)"); patches (bottom)/fsiCoupling; libs ("\1"); patches (botom)/' system/controlDict ;;
  bad-scene) sed -i 's/rho 1.2; pRef 0; }/rho 1.2; pRef 0; scene "missing.yaml"; }/' system/controlDict ;;
  missing-library) sed -i '/^libs (/d' system/controlDict ;;
esac
blockMesh > log.blockMesh 2>&1 || { echo "blockMesh failed"; cat log.blockMesh; exit 1; }
pimpleFoam > log.pimpleFoam 2>&1
rc=$?
fail() { echo "FAIL: $*"; tail -30 log.pimpleFoam; exit 1; }
case "$mode" in
  forces)
    [ $rc -eq 0 ] || fail "pimpleFoam exited with $rc"
    grep -q "fsiCoupling: t = " log.pimpleFoam || fail "the function object did not run"
    ours=$(grep "interface pressure force" log.pimpleFoam | tail -n 1 | sed 's/.*force (\(.*\)) N/\1/')
    theirs=$(awk '/Sum of forces/{s=1} s&&/Pressure :/{v=$0; s=0} END{print v}' log.pimpleFoam | sed 's/.*(\(.*\))/\1/')
    echo "fsiCoupling: ($ours)  forces: ($theirs)"
    python3 - "$ours" "$theirs" <<'PY' || fail "forces differ"
import sys
a = [float(v) for v in sys.argv[1].split()]
b = [float(v) for v in sys.argv[2].split()]
scale = max(max(abs(v) for v in b), 1e-300)
err = max(abs(x - y) for x, y in zip(a, b)) / scale
print(f"relative difference {err:.2e}")
sys.exit(0 if len(a) == 3 and len(b) == 3 and err < 1e-6 else 1)
PY
    ;;
  wrong-patch)
    [ $rc -ne 0 ] || fail "a wrong patch name must stop the run"
    grep -q "no patch named botom" log.pimpleFoam || fail "the message does not name the patch"
    ;;
  moving)
    [ $rc -eq 0 ] || fail "pimpleFoam exited with $rc"
    grep -q "fsiCoupling: t = " log.pimpleFoam || fail "the function object did not run"
    ;;
  missing-library)
    [ $rc -ne 0 ] || fail "a run without the adapter library must not go on uncoupled"
    grep -q "Unknown patchField type fsiInterfaceDisplacement" log.pimpleFoam || fail "no clear message"
    ;;
  bad-scene)
    [ $rc -ne 0 ] || fail "a missing scene must stop the run"
    grep -q "missing.yaml" log.pimpleFoam || fail "the message does not name the scene"
    ;;
esac
echo "PASS $mode"
