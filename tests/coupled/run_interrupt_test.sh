#!/usr/bin/env bash
# Ctrl-C, SIGTERM and restarts of a coupled case's Allrun (issue 35 items 1-3; cases/coupled/run-functions.sh,
# adapter/fsiStopRequest.H), on copies of cavity-membrane-2d (implicit, IQN-ILS with reuse 8). Modes:
#   signal SIG  ./Allrun 10 is sent SIG (INT or TERM) a few windows in, before its first write time (t = 1 s):
#               it exits 130 (INT) or 143 (TERM) with one line naming `./Allrun -continue`; the fields and the
#               structure's state are written at the stop's time T < 1 s (U, uniform/fsiStructure.h5,
#               structure/interrupted); `./Allrun -continue 1.5` then goes on from T and its answer equals a run
#               straight to 1.5 s to the coupling tolerance. While it runs, a second Allrun in the folder is
#               refused (exit 2, naming the running one's pid and how to stop it).
#   parallel    the same with ./Allrun.parallel (2 ranks) and SIGINT: every rank's fields at T, -continue on 2 ranks
#               (to 0.3 s)
#   iterations  a restart iterates like the run it continues: to 0.03 s, then -continue 0.3, both writing 17
#               digits: every window takes the uninterrupted run's iteration count and the answer is the same
#               to round-off (the IQN-ILS columns, the structure and the fluid's reference come back exactly)
#   deadend     a run killed (SIGKILL) before it wrote anything: ./Allrun and ./Allrun -continue are refused with
#               a command that works (./Allclean && ./Allrun), and that command runs
# Usage: run_interrupt_test.sh MODE BUILD_DIR WORK_DIR [SIG]
set -uo pipefail
mode=$1 build=$2 work=$3 sig=${4:-INT}
repo="$(cd "$(dirname "$0")/../.." && pwd)"
src=$repo/cases/coupled
case=$src/cavity-membrane-2d
fail() { echo "FAIL: $*"; exit 1; }
command -v blockMesh > /dev/null || { echo "no OpenFOAM: skipped"; exit 77; }
. "$build/share/fsi/fsi-env.sh" > /dev/null || fail "sourcing $build/share/fsi/fsi-env.sh"
. "$(dirname "$0")/case-test-functions.sh"   # last_probe, close
# windows CASE: rows of structure/coupling.csv so far (0 if none)
windows() {
  local n=0
  [ -f "$1/structure/coupling.csv" ] && n=$(grep -vc '^[#t]' "$1/structure/coupling.csv")
  echo "${n:-0}"
}
# iterations CASE: the iteration count of every window, space-separated
iterations() {
  /usr/bin/python3 -c "
import csv, sys
print(' '.join(r['iterations'] for r in csv.DictReader(l for l in open(sys.argv[1] + '/structure/coupling.csv') if not l.startswith('#'))))" "$1"
}

# interrupted CASE RUNNER SIG: starts RUNNER 10 in CASE, checks the lock while it runs, sends SIG after 5 windows;
# checks the exit code, the message and what was written; sets T (the stop's time)
interrupted() {
  local dir=$1 runner=$2 s=$3 code=130 pid n=0
  [ "$s" = TERM ] && code=143
  cd "$dir" || exit 1
  # with job control, as from a terminal: a background job of a script without it ignores SIGINT
  set -m
  "$runner" 10 > ../run.out 2>&1 &
  pid=$!
  set +m
  while [ "$(windows .)" -lt 5 ]; do
    sleep 0.1
    n=$((n + 1))
    [ $n -lt 600 ] || { kill -KILL $pid; cat ../run.out; fail "no 5 windows after 60 s"; }
  done
  "$runner" 10 > ../second.out 2>&1
  local rc=$?
  cat ../second.out
  [ $rc -eq 2 ] && grep -q "another Allrun runs in .* (pid $pid)" ../second.out && grep -q "kill -INT $pid" ../second.out ||
    fail "a second Allrun while one runs: exit $rc, not refused naming pid $pid"
  kill -"$s" $pid
  wait $pid
  rc=$?
  cat ../run.out
  [ $rc -eq $code ] || fail "SIG$s: Allrun exited $rc, not $code"
  grep -q "^Allrun: stopped on SIG$s at t = .* $runner -continue" ../run.out || fail "no line naming $runner -continue"
  [ -f structure/interrupted ] || fail "no structure/interrupted"
  T=$(sed -n 's/^time //p' structure/interrupted)
  /usr/bin/python3 -c "import sys; sys.exit(0 if 0 < float(sys.argv[1]) < 1 else 1)" "$T" ||
    fail "stopped at t = $T: not before the first write time 1 s"
  local d
  local dirs=(.)
  [ "$runner" = ./Allrun.parallel ] && dirs=(processor0 processor1)
  for d in "${dirs[@]}"; do
    [ -f "$d/$T/U" ] && [ -f "$d/$T/p" ] || fail "no fields at $d/$T"
  done
  local state=$T/uniform/fsiStructure.h5
  [ "$runner" = ./Allrun.parallel ] && state=processor0/$state
  [ -f "$state" ] || fail "no structure state $state"
  [ ! -e fsi.stop ] || fail "the stop file was left behind"
  echo "stopped on SIG$s at t = $T ($(windows .) windows written)"
}

case "$mode" in
  signal | parallel)
    runner=./Allrun
    [ "$mode" = parallel ] && runner=./Allrun.parallel sig=INT
    rm -rf "$work" && mkdir -p "$work/straight" "$work/stopped"
    cp -r "$case" "$work/straight/case" && cp -r "$case" "$work/stopped/case"
    interrupted "$work/stopped/case" "$runner" "$sig"
    # to 1.5 s serial; 0.3 s on 2 ranks (a 2-rank window of this case costs about 30 times a serial one here)
    end=1.5
    [ "$mode" = parallel ] && end=0.3
    "$runner" -continue $end > ../continue.out 2>&1 || { cat ../continue.out; fail "$runner -continue $end failed"; }
    grep -q "structure restarted from" log.pimpleFoam.1 || fail "the continued run did not restart the structure"
    (cd "$work/straight/case" && "$runner" $end > ../run.out 2>&1) || { cat "$work/straight/run.out"; fail "the straight run failed"; }
    # Equal to the coupling tolerance (the case's 1e-6; the decomposed solvers' floor of 5e-5 on 2 ranks, see
    # run_allrun_test.sh parallel): the restart continues fields written with 12 digits.
    tol=1e-5
    [ "$mode" = parallel ] && tol=5e-5
    close "$(last_probe "$work/straight/case")" "$(last_probe "$work/stopped/case")" "$tol" ||
      fail "the interrupted and continued run differs from the straight one"
    ;;
  iterations)
    rm -rf "$work" && mkdir -p "$work/straight" "$work/restarted"
    cp -r "$case" "$work/straight/case" && cp -r "$case" "$work/restarted/case"
    # Both copies write 17 digits (the case's 12 round the fields the restart reads back): then -continue is
    # the uninterrupted run bit for bit, with the run's projection defaults (docs/ROBUSTNESS.md). The implicit
    # iterations are sensitive to round-off (12 or 17 digits in the first mesh alone change the counts from
    # the second window on), so equal counts in every window show that nothing of the state is lost.
    for c in "$work/straight/case" "$work/restarted/case"; do
      sed -i 's/writePrecision 12;/writePrecision 17;/' "$c/system/controlDict"
      grep -q "writePrecision 17;" "$c/system/controlDict" || fail "could not set writePrecision 17 in $c"
    done
    (cd "$work/straight/case" && ./Allrun 0.3 > ../run.out 2>&1) || fail "the straight run failed"
    cd "$work/restarted/case" || exit 1
    ./Allrun 0.03 > ../first.out 2>&1 || fail "the run to 0.03 failed"
    ./Allrun -continue 0.3 > ../continue.out 2>&1 || { cat ../continue.out; fail "-continue 0.3 failed"; }
    a=($(iterations "$work/straight/case")) b=($(iterations .))
    echo "iterations per window, straight:   ${a[*]:0:12}"
    echo "iterations per window, restarted:  ${b[*]:0:12}"
    [ "${#a[@]}" = 30 ] && [ "${#b[@]}" = 30 ] || fail "not 30 windows each (${#a[@]}, ${#b[@]})"
    # every window after the restart at 0.03 s (windows 4-30) as the uninterrupted run's
    [ "${a[*]}" = "${b[*]}" ] || fail "the restarted run's iterations differ from the uninterrupted run's"
    close "$(last_probe "$work/straight/case")" "$(last_probe .)" 1e-12 ||
      fail "the restarted run's answer is not the uninterrupted run's to round-off"
    ;;
  deadend)
    rm -rf "$work" && mkdir -p "$work" && cp -r "$case" "$work/case" && cd "$work/case" || exit 1
    # killed hard while the solver starts: nothing written after t = 0, leftovers (log, structure/)
    ./Allrun 10 > ../run.out 2>&1 &
    pid=$!
    while [ ! -s log.pimpleFoam ] || [ ! -s .fsi.pid ]; do sleep 0.05; done
    # this case's solver only (its own session: the pid in .fsi.pid leads its process group), then Allrun
    kill -KILL -- "-$(tr -cd '0-9' < .fsi.pid)" 2> /dev/null
    kill -KILL $pid 2> /dev/null
    wait $pid 2> /dev/null
    sleep 0.5
    ls -d [1-9]* 0.[0-9]* 2> /dev/null && fail "the killed run wrote a time directory: not the case tested"
    for args in "" "-continue"; do
      ./Allrun $args 10 > ../refused.out 2>&1
      rc=$?
      cat ../refused.out
      [ $rc -eq 2 ] && grep -q "./Allclean && ./Allrun" ../refused.out || fail "./Allrun $args: exit $rc, not refused naming ./Allclean && ./Allrun"
    done
    (./Allclean && ./Allrun 0.05) > ../again.out 2>&1 || { cat ../again.out; fail "./Allclean && ./Allrun failed"; }
    [ -f 0.05/U ] || fail "./Allclean && ./Allrun did not run"
    ;;
  *) fail "unknown mode $mode" ;;
esac
echo "PASS $mode $sig"
