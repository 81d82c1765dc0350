#!/usr/bin/env bash
# Runs Debian's pimpleFoam with the fsiFoam library on the tiny test cases, in one of the modes:
#   forces          : monitor mode; the interface pressure force equals OpenFOAM's `forces` object (1e-6)
#   forces-viscous  : the same for the viscous force (option `viscous yes`)
#   wrong-patch     : a misspelt patch name stops the solver with a non-zero exit and names the patch
#   bad-scene       : a missing structure scene stops the solver and names the file
#   missing-library : without the library the interface boundary condition is a hard error
#   no-coupling     : the boundary condition without the fsiCoupling object stops at the first mesh motion
#   missing-bc      : U on the interface without movingWallVelocity is refused at start-up
#   unstable        : a structure stepped above its stability limit stops the run with the structure's
#                     diagnosis (not OpenFOAM's floating-point trap) and keeps its last stable state
#   coupled         : staggered coupled run: the bottom rises, fluid and structure interface forces agree
#                     (< 1e-6 relative, every window), results and restart state are written
#   checkpoint      : implicit coupling with every pass repeated from its checkpoint: the repeat is exact
#   parallel        : the coupled run on 2 MPI ranks (cut across the interface) equals the serial one
#   restart         : stop at t = 0.25, restart from that time directory, compare with the continuous run
#   subcycles       : 1 vs 10 structural steps per fluid step differ less than the coupled time-step error
#   convergence     : halving the fluid step: successive differences of the answer shrink (order > 0.7)
# Usage: run_adapter_test.sh MODE ADAPTER_LIB WORK_DIR
set -uo pipefail
mode=$1 lib=$2 work=$3
here="$(cd "$(dirname "$0")" && pwd)"
export WM_PROJECT_DIR=/usr/share/openfoam
case_dir=cavity-moving
case "$mode" in forces|forces-viscous|wrong-patch) case_dir=cavity ;; esac
rm -rf "$work" && mkdir -p "$work"

fail() { echo "FAIL: $*"; [ -f "${log:-}" ] && tail -30 "$log"; exit 1; }

# prepare DIR: a fresh copy of the case with the library path filled in and its mesh
prepare() {
  local dir=$1
  mkdir -p "$dir" && cp -r "$here/$case_dir/." "$dir/"
  sed -i "s|FSI_ADAPTER_LIB|$lib|" "$dir/system/controlDict"
  (cd "$dir" && blockMesh > log.blockMesh 2>&1) || fail "blockMesh failed in $dir"
}
# set DIR KEY VALUE: change a top-level controlDict entry
set_entry() { sed -i "s|\b$2 [^;]*;|$2 $3;|" "$1/system/controlDict"; }
# fsi_option DIR TEXT: add entries to the fsiCoupling dictionary
fsi_option() { sed -i "s|scene \"structure.yaml\";|scene \"structure.yaml\"; $2|" "$1/system/controlDict"; }
# solve DIR [NP]: run pimpleFoam (serial or on NP ranks); sets rc and log
solve() {
  local dir=$1 np=${2:-1}
  log="$dir/log.pimpleFoam"
  if [ "$np" -gt 1 ]; then
    (cd "$dir" && decomposePar -force > log.decomposePar 2>&1) || fail "decomposePar failed"
    (cd "$dir" && mpirun -np "$np" --allow-run-as-root --oversubscribe pimpleFoam -parallel > log.pimpleFoam 2>&1)
  else
    (cd "$dir" && pimpleFoam > log.pimpleFoam 2>&1)
  fi
  rc=$?
}
# last DIR COLUMN: value of COLUMN in the last row of structure/coupling*.csv (newest file)
last() { python3 - "$1" "$2" <<'PY'
import csv, glob, os, sys
files = sorted(glob.glob(os.path.join(sys.argv[1], "structure", "coupling*.csv")), key=os.path.getmtime)
rows = list(csv.DictReader(open(files[-1])))
print(rows[-1][sys.argv[2]])
PY
}
check_conservation() {
  python3 "$here/../../cases/coupled/summarize.py" --force-check "$1" || fail "fluid and structure interface forces differ"
}
# close A B TOL: |A - B| <= TOL * max(|A|, |B|)
close() { python3 -c "import sys; a, b, t = map(float, sys.argv[1:]); print(f'{a:.9g} vs {b:.9g}: relative difference {abs(a-b)/max(abs(a),abs(b)):.2e} (limit {t:g})'); sys.exit(0 if abs(a-b) <= t*max(abs(a),abs(b)) else 1)" "$@"; }

case "$mode" in
  forces|forces-viscous|wrong-patch|bad-scene)
    prepare "$work/case"
    case "$mode" in
      forces-viscous) sed -i 's/rho 1.2; pRef 0; }/rho 1.2; pRef 0; viscous yes; }/' "$work/case/system/controlDict" ;;
      wrong-patch) sed -i 's/fsiCoupling; libs ("\([^"]*\)"); patches (bottom)/fsiCoupling; libs ("\1"); patches (botom)/' "$work/case/system/controlDict" ;;
      bad-scene) sed -i 's/scene "structure.yaml";/scene "missing.yaml";/' "$work/case/system/controlDict" ;;
    esac
    solve "$work/case"
    case "$mode" in
      forces|forces-viscous)
        [ $rc -eq 0 ] || fail "pimpleFoam exited with $rc"
        grep -q "fsiCoupling: t = " "$log" || fail "the function object did not run"
        if [ "$mode" = forces ]; then
          ours=$(grep "interface pressure force" "$log" | tail -n 1 | sed 's/.*pressure force (\([^)]*\)) N.*/\1/')
          theirs=$(awk '/Sum of forces/{s=1} s&&/Pressure :/{v=$0; s=0} END{print v}' "$log" | sed 's/.*(\(.*\))/\1/')
        else
          ours=$(grep "viscous force" "$log" | tail -n 1 | sed 's/.*viscous force (\([^)]*\)) N.*/\1/')
          theirs=$(awk '/Sum of forces/{s=1} s&&/Viscous *:/{v=$0; s=0} END{print v}' "$log" | sed 's/.*(\(.*\))/\1/')
        fi
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
        grep -q "no patch named botom" "$log" || fail "the message does not name the patch" ;;
      bad-scene)
        [ $rc -ne 0 ] || fail "a missing scene must stop the run"
        grep -q "missing.yaml" "$log" || fail "the message does not name the scene" ;;
    esac
    ;;
  missing-library)
    prepare "$work/case"
    sed -i '/^libs (/d' "$work/case/system/controlDict"
    solve "$work/case"
    [ $rc -ne 0 ] || fail "a run without the adapter library must not go on uncoupled"
    grep -q "Unknown patchField type fsiInterfaceDisplacement" "$log" || fail "no clear message"
    ;;
  no-coupling)
    prepare "$work/case"
    sed -i '/fsi { type fsiCoupling/d' "$work/case/system/controlDict"
    solve "$work/case"
    [ $rc -ne 0 ] || fail "a run whose coupling never starts must stop"
    grep -q "the coupling did not start" "$log" || fail "no clear message"
    ;;
  missing-bc)
    prepare "$work/case"
    sed -i 's/bottom { type movingWallVelocity; value uniform (0 0 0); }/bottom { type noSlip; }/' "$work/case/0/U"
    solve "$work/case"
    [ $rc -ne 0 ] || fail "U without movingWallVelocity on the interface must be refused"
    grep -q "U on patch bottom is of type noSlip; a moving interface needs movingWallVelocity" "$log" || fail "no clear message"
    ;;
  unstable)
    prepare "$work/case"
    # 1e7 times stiffer: critical step about 1.1e-5 s, forced to 1e-4 s (100 steps per window: overflow)
    sed -i 's/young: 250,/young: 2.5e9,/' "$work/case/structure.yaml"
    echo "time: {fixed_dt: 0.0001}" >> "$work/case/structure.yaml"
    solve "$work/case"
    [ $rc -ne 0 ] || fail "an unstable structure must stop the run"
    grep -q "the structure became unstable: instability at step" "$log" || fail "no diagnosis from the structure"
    grep -q "Last stable state: step" "$log" || fail "the diagnosis does not name the last stable state"
    ! grep -q "sigFpe" "$log" || fail "the run died on a floating-point trap instead of the diagnosis"
    /usr/bin/python3 -c "import h5py, sys; f = h5py.File(sys.argv[1]); print('last stable state at t =', f.attrs['time'] if 'time' in f.attrs else list(f.keys()))" \
      "$work/case/structure/last_stable_state.h5" || fail "no readable structure/last_stable_state.h5"
    ;;
  coupled)
    prepare "$work/case"
    solve "$work/case"
    [ $rc -eq 0 ] || fail "pimpleFoam exited with $rc"
    check_conservation "$work/case"
    z=$(last "$work/case" mid_z)
    python3 -c "import sys; z = float(sys.argv[1]); print(f'mid-point rise {z:.4g} m'); sys.exit(0 if 1e-3 < z < 0.1 else 1)" "$z" \
      || fail "the bottom did not rise as expected"
    for f in structure/results.h5 structure/results.xdmf structure/timing.json 0.25/uniform/fsiStructure.h5 0.5/uniform/fsiStructure.h5; do
      [ -s "$work/case/$f" ] || fail "missing output $f"
    done
    ;;
  checkpoint)
    prepare "$work/case"
    fsi_option "$work/case" "scheme implicit; verifyCheckpoint yes;"
    set_entry "$work/case" endTime 0.1
    solve "$work/case"
    [ $rc -eq 0 ] || fail "pimpleFoam exited with $rc"
    python3 - "$log" <<'PY' || fail "a repeated pass differs from the first"
import re, sys
lines = [l for l in open(sys.argv[1]) if "repeated window" in l]
worst = max((float(v) for l in lines for v in re.findall(r"\| ([-0-9.e+]+)", l)), default=None)
iters = [int(m) for m in re.findall(r"window \d+: (\d+) iteration", open(sys.argv[1]).read())]
print(f"{len(lines)} repeated passes over {len(iters)} windows ({sum(iters)} coupling iterations); largest difference {worst}")
sys.exit(0 if lines and worst == 0.0 and max(iters) > 1 and len(lines) == sum(iters) else 1)
PY
    ;;
  parallel)
    prepare "$work/serial"
    prepare "$work/parallel"
    solve "$work/serial"
    [ $rc -eq 0 ] || fail "serial pimpleFoam exited with $rc"
    solve "$work/parallel" 2
    [ $rc -eq 0 ] || fail "parallel pimpleFoam exited with $rc"
    grep -q "22 fluid points" "$work/parallel/log.pimpleFoam" || fail "the 2-rank interface does not have the serial 22 points"
    check_conservation "$work/parallel"
    close "$(last "$work/serial" mid_z)" "$(last "$work/parallel" mid_z)" 1e-5 || fail "serial and 2-rank answers differ"
    ;;
  restart)
    prepare "$work/continuous"
    solve "$work/continuous"
    [ $rc -eq 0 ] || fail "continuous run exited with $rc"
    prepare "$work/restarted"
    set_entry "$work/restarted" endTime 0.25
    solve "$work/restarted"
    [ $rc -eq 0 ] || fail "first half exited with $rc"
    set_entry "$work/restarted" endTime 0.5
    set_entry "$work/restarted" startFrom latestTime
    solve "$work/restarted"
    [ $rc -eq 0 ] || fail "restarted run exited with $rc"
    grep -q "structure restarted from" "$log" || fail "the structure did not restart from its state"
    close "$(last "$work/continuous" mid_z)" "$(last "$work/restarted" mid_z)" 1e-7 || fail "restart changed the answer"
    ;;
  subcycles)
    # Subcycling must be consistent: its effect is of the order of the coupled time-step error and
    # vanishes with the step like it (it must not leave a step-independent offset).
    for k in 1 2; do for n in 1 10; do
      d=$(python3 -c "print(0.01/$k)"); w=$((25 * k))
      prepare "$work/dt$k-sub$n"; fsi_option "$work/dt$k-sub$n" "subcycles $n;"
      set_entry "$work/dt$k-sub$n" deltaT "$d"; set_entry "$work/dt$k-sub$n" writeInterval "$w"; solve "$work/dt$k-sub$n"
      [ $rc -eq 0 ] || fail "deltaT $d, subcycles $n exited with $rc"
    done; done
    grep -q " 10 structural steps per window" "$work/dt1-sub10/log.pimpleFoam" || fail "subcycling was not applied"
    python3 - "$(last "$work/dt1-sub1" mid_z)" "$(last "$work/dt1-sub10" mid_z)" "$(last "$work/dt2-sub1" mid_z)" \
      "$(last "$work/dt2-sub10" mid_z)" <<'PY' || fail "subcycling changes the answer beyond the time-discretisation error"
import sys
a1, a10, b1, b10 = map(float, sys.argv[1:])
d_a, d_b, step = abs(a1 - a10), abs(b1 - b10), abs(a1 - b1)
print(f"dt 0.01: subcycles 1 {a1:.9g}, 10 {a10:.9g} (difference {d_a:.3e}); halving the step changes the answer by {step:.3e}")
print(f"dt 0.005: subcycles 1 {b1:.9g}, 10 {b10:.9g} (difference {d_b:.3e}, ratio {d_a / d_b:.2f})")
sys.exit(0 if d_a <= 2.0 * step and d_b < 0.7 * d_a else 1)
PY
    ;;
  convergence)
    values=()
    for k in 1 2 4; do
      d=$(python3 -c "print(0.02/$k)"); w=$((25 * k / 2))
      prepare "$work/dt$k"; set_entry "$work/dt$k" deltaT "$d"; set_entry "$work/dt$k" writeInterval "$w"; solve "$work/dt$k"
      [ $rc -eq 0 ] || fail "deltaT $d exited with $rc"
      values+=("$(last "$work/dt$k" mid_z)")
    done
    python3 - "${values[@]}" <<'PY' || fail "the coupled answer does not converge with the step"
import math, sys
z1, z2, z4 = map(float, sys.argv[1:])
e1, e2 = abs(z1 - z2), abs(z2 - z4)
order = math.log2(e1 / e2) if e2 > 0 else float("inf")
print(f"mid-point rise at t = 0.5 s: dt 0.02 {z1:.9g}, 0.01 {z2:.9g}, 0.005 {z4:.9g}; observed order {order:.2f}")
sys.exit(0 if order > 0.7 else 1)
PY
    ;;
  *) fail "unknown mode $mode" ;;
esac
echo "PASS $mode"
