#!/usr/bin/env bash
# How a user runs the coupled cases: copied anywhere, after sourcing an fsi-env.sh, serial or parallel,
# continued, cleaned. Short end times (a few seconds of pimpleFoam each); the full-length runs are the
# coupled.<case> tests. Modes:
#   install           cmake --install into WORK/prefix; a case copied to WORK/run refuses to start with nothing
#                     sourced (exit 2, a message naming fsi-env.sh), runs to its end after
#                     `. WORK/prefix/share/fsi/fsi-env.sh` (progress on the console, summary.json, CASE.foam,
#                     plots/*.png when the fsi command has `plot`, else a note),
#                     and runs with only WORK/prefix/bin on PATH
#   continue          (the copy of `install`) ./Allrun again is refused with exit 2 and a one-line message and
#                     leaves summary.json alone; -continue without a later end time is refused; -continue END
#                     goes on to END and equals a run straight to END (to the coupling tolerance)
#   parallel NAME END Allrun.parallel (2 ranks, the interface split between them) equals the serial Allrun (to the coupling tolerance)
#   tracked NAME END  in a copy of the source tree with build/ beside it and nothing sourced: Allrun then
#                     Allclean leave every tracked case file as it was and nothing else; all that Allrun
#                     writes is git-ignored, no tracked file is
# Usage: run_allrun_test.sh MODE BUILD_DIR WORK_DIR [NAME END]
set -uo pipefail
mode=$1 build=$2 work=$3 name=${4:-cavity-membrane-2d} end=${5:-0.1}
repo="$(cd "$(dirname "$0")/../.." && pwd)"
src=$repo/cases/coupled
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}   # for foamDictionary here

fail() { echo "FAIL: $*"; exit 1; }
# clean CMD...: runs CMD with nothing of this environment (no fsi-env.sh, no build folders on any path)
clean() { env -i HOME="$HOME" PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin LANG=C.UTF-8 "$@"; }
# with_env ENV_SCRIPT CMD...: runs CMD in a clean environment after sourcing ENV_SCRIPT
with_env() { local e=$1; shift; clean bash -c '. "$0" && exec "$@"' "$e" "$@"; }
# json FILE EXPR: a value of summary.json (python expression on s)
json() { /usr/bin/python3 -c "import json, sys; s = json.load(open(sys.argv[1])); print($2)" "$1"; }
. "$(dirname "$0")/case-test-functions.sh"   # last_probe, close
# force_close SERIAL PARALLEL LIMIT: the interface force of every window (structure/coupling.csv, fluid side)
# agrees between the two runs within LIMIT of the largest force of the serial run
force_close() {
  /usr/bin/python3 - "$1" "$2" "$3" "$src" <<'PY'
import sys
sys.path.insert(0, sys.argv[4])
import summarize
s, p = summarize.coupling_rows(sys.argv[1]), summarize.coupling_rows(sys.argv[2])
limit = float(sys.argv[3])
if len(s) != len(p) or not s:
    sys.exit(f"serial has {len(s)} windows, parallel {len(p)}")
keys = ("Fx_fluid", "Fy_fluid", "Fz_fluid")
def vec(r):
    return [float(r[k]) for k in keys]
scale = max(sum(x * x for x in vec(r)) ** 0.5 for r in s)
worst, when = max((sum((a - b) ** 2 for a, b in zip(vec(x), vec(y))) ** 0.5, x["time"]) for x, y in zip(s, p))
print(f"interface force, serial vs 2 ranks over {len(s)} windows: largest difference {worst:.3g} N at t = {when} "
      f"= {worst / scale:.2e} of the largest force {scale:.3g} N (limit {limit:g})")
sys.exit(0 if worst <= limit * scale else 1)
PY
}
# reached CASE END: summary.json says the run ended at END
reached() {
  local t
  t=$(json "$1/summary.json" 's["end_time"]')
  /usr/bin/python3 -c "import sys; sys.exit(0 if abs(float(sys.argv[1]) - float(sys.argv[2])) < 1e-9 else 1)" "$t" "$2" ||
    fail "$1 ended at t = $t, not $2"
}

case "$mode" in
  install)
    rm -rf "$work" && mkdir -p "$work/run"
    cmake --install "$build" --prefix "$work/prefix" > "$work/install.log" 2>&1 || { cat "$work/install.log"; fail "cmake --install failed"; }
    for f in bin/fsi lib/libfsiFoam.so share/fsi/fsi-env.sh share/fsi/case-functions.sh share/fsi/summarize.py \
      share/fsi/ramair_fluid.py share/fsi/ramair_settings.py share/fsi/ramair_geometry.py share/fsi/ramair_dicts.py \
      share/fsi/ramair_fields.py share/fsi/ramair_mesh.py share/fsi/ramair_summary.py share/fsi/ramair_wing.py; do
      [ -f "$work/prefix/$f" ] || fail "the install has no $f"
    done
    ! readelf -d "$work/prefix/lib/libfsiFoam.so" | grep -q "$build" || fail "the installed library refers to the build tree"
    cp -r "$src/$name" "$work/run/"
    cp -r "$src/$name" "$work/run/$name-path"
    cd "$work/run/$name" || exit 1
    clean ./Allrun "$end" > ../nothing.out 2>&1
    rc=$?
    cat ../nothing.out
    [ $rc -eq 2 ] || fail "with nothing sourced Allrun exited with $rc, not 2"
    [ "$(wc -l < ../nothing.out)" -eq 1 ] && grep -q ". <build or install prefix>/share/fsi/fsi-env.sh" ../nothing.out ||
      fail "the message does not say what to source"
    with_env "$work/prefix/share/fsi/fsi-env.sh" ./Allrun "$end" > ../allrun.out 2>&1 || { cat ../allrun.out; fail "Allrun failed"; }
    cat ../allrun.out
    grep -qE '^(\[fsi\] |fsiCoupling: )' ../allrun.out || fail "no progress lines on the console"
    grep -q "wall time" ../allrun.out && grep -q "coupling iterations per window" ../allrun.out || fail "no summary on the console"
    ! grep -q '^{' ../allrun.out || fail "raw JSON on the console"
    reached . "$end"
    [ -f "$name.foam" ] || fail "no $name.foam for ParaView"
    if "$work/prefix/bin/fsi" --help | grep -qE '^ +plot '; then
      ls plots/*.png > /dev/null 2>&1 || fail "fsi has a plot command but Allrun made no plots/*.png"
    else
      grep -q "no plots (this fsi command has no 'plot')" ../allrun.out || fail "no note that plots were skipped"
    fi
    [ -s log.pimpleFoam ] && grep -q "^Time = " log.pimpleFoam || fail "the solver's full output is not in log.pimpleFoam"
    # only the install's bin/ on PATH, nothing sourced
    cd "$work/run/$name-path" || exit 1
    clean env PATH="$work/prefix/bin:/usr/sbin:/usr/bin:/sbin:/bin" ./Allrun "$end" > ../path.out 2>&1 || { cat ../path.out; fail "Allrun with the install's bin/ on PATH failed"; }
    reached . "$end"
    ;;
  continue)
    dir=$work/run/$name
    [ -f "$dir/summary.json" ] || fail "no finished run from the install test in $dir"
    env=$work/prefix/share/fsi/fsi-env.sh
    cd "$dir" || exit 1
    before=$(sha256sum summary.json)
    with_env "$env" ./Allrun "$end" > ../again.out 2>&1
    rc=$?
    cat ../again.out
    [ $rc -eq 2 ] || fail "a second Allrun exited with $rc, not 2"
    [ "$(wc -l < ../again.out)" -eq 1 ] && grep -q "./Allclean" ../again.out && grep -q -- "-continue" ../again.out ||
      fail "the refusal is not one line naming ./Allclean and -continue"
    [ "$(sha256sum summary.json)" = "$before" ] || fail "the refused run changed summary.json"
    with_env "$env" ./Allrun -continue "$end" > ../same.out 2>&1
    rc=$?
    cat ../same.out
    [ $rc -eq 2 ] && grep -q "already reached" ../same.out || fail "-continue to the time already reached: exit $rc"
    end2=$(/usr/bin/python3 -c "print(2 * $end)")
    with_env "$env" ./Allrun -continue "$end2" > ../continue.out 2>&1 || { cat ../continue.out; fail "Allrun -continue failed"; }
    cat ../continue.out
    reached . "$end2"
    grep -q "structure restarted from" log.pimpleFoam.1 || fail "the structure did not restart from its state"
    windows=$(json summary.json 's["iterations"]["windows"]')
    steps=$(/usr/bin/python3 -c "print(round($end2 / $(foamDictionary -entry deltaT -value system/controlDict)))")
    [ "$windows" = "$steps" ] || fail "summary.json counts $windows windows, not $steps"
    # the same case straight to end2
    rm -rf "$work/straight" && mkdir -p "$work/straight" && cp -r "$src/$name" "$work/straight/"
    (cd "$work/straight/$name" && with_env "$env" ./Allrun "$end2" > ../straight.out 2>&1) || fail "the straight run failed"
    # Equal to the coupling's convergence tolerance: the continued run restarts the structure, the interface
    # history and IQN-ILS' reused columns exactly, but from fluid fields written with 12 digits, so a window
    # can converge along another path, to within `tolerance` (relative) of the same answer.
    # The case's tolerance, or the adapter's default where the case leaves it (sail-2d).
    tol=$(foamDictionary -entry functions/fsi/tolerance -value system/controlDict 2>/dev/null || echo 1e-5)
    close "$(last_probe "$work/straight/$name")" "$(last_probe "$dir")" "$tol" || fail "continuing changed the answer"
    ;;
  parallel)
    rm -rf "$work" && mkdir -p "$work/serial" "$work/parallel"
    cp -r "$src/$name" "$work/serial/" && cp -r "$src/$name" "$work/parallel/"
    env=$build/share/fsi/fsi-env.sh
    (cd "$work/serial/$name" && with_env "$env" ./Allrun "$end" > ../allrun.out 2>&1) || { cat "$work/serial/allrun.out"; fail "serial Allrun failed"; }
    cd "$work/parallel/$name" || exit 1
    with_env "$env" ./Allrun.parallel "$end" > ../allrun.out 2>&1 || { cat ../allrun.out; fail "Allrun.parallel failed"; }
    cat ../allrun.out
    reached . "$end"
    [ "$(json summary.json 's["coupling"]["ranks"]')" = 2 ] || fail "the run did not use 2 ranks"
    # every coupled patch has faces on both ranks (the cut splits the interface)
    patches=$(foamDictionary -entry functions/fsi/patches -value system/controlDict | tr -d '()')
    for p in $patches; do
      for r in 0 1; do
        n=$(awk -v p="$p" '$1 == p { f = 1 } f && $1 == "nFaces" { print $2 + 0; exit }' "processor$r/constant/polyMesh/boundary")
        echo "patch $p: $n faces on rank $r"
        [ "$n" -gt 0 ] || fail "patch $p has no faces on rank $r: the decomposition does not split the interface"
      done
    done
    [ -f "$end/U" ] || fail "reconstructPar did not write $end/U"
    s=$(grep -o "[0-9]* fluid points" "$work/serial/$name/log.pimpleFoam")
    p=$(grep -o "[0-9]* fluid points" log.pimpleFoam)
    [ "$s" = "$p" ] || fail "the interface has $p in parallel, $s serial"
    # To the coupling's convergence tolerance: both runs end each window within `tolerance` (relative) of its
    # fixed point, and the decomposed linear solvers and IQN-ILS reach it along different paths. (The
    # adapter's own parallel test, staggered coupling, is held to 1e-5.) A lost or doubled part of the
    # interface on one rank changes the answer by far more.
    # The case's tolerance, or the adapter's default where the case leaves it (sail-2d) -- but not below 5e-5:
    # the decomposed fluid solvers (processor-local DIC) leave a floor that a tighter coupling tolerance does
    # not lower (cavity-membrane-2d, mid-point at 0.2 / 1 s: 2.5e-5 / 1.0e-5 at tolerance 1e-4, 2.0e-5 /
    # 0.9e-5 at 1e-6; docs/VALIDATION.md).
    tol=$(foamDictionary -entry functions/fsi/tolerance -value system/controlDict 2>/dev/null || echo 1e-5)
    tol=$(/usr/bin/python3 -c "import sys; print(max(float(sys.argv[1]), 5e-5))" "$tol")
    close "$(last_probe "$work/serial/$name")" "$(last_probe .)" "$tol" || fail "serial and 2-rank answers differ"
    # The interface force too, window by window (issue 15: at the cavity's old tolerance 1e-4 the two runs' Fz
    # differed by a third of Fz, from the iteration error's acceleration noise). The force is the displacement's
    # second difference over the window times the added mass, so it carries the floor above amplified. Measured
    # (2026-11-28, the test's END): cavity 7.5e-5 of the largest force (tolerance 1e-6; 3.4e-3 at its old 1e-4),
    # inflated-patch 3.3e-5, baffle-canopy 4.2e-4, sail 1.0e-5. 1e-3 leaves room for those and still fails for
    # the cavity's old noise or a part of the interface lost on one rank.
    force_close "$work/serial/$name" . 1e-3 || fail "serial and 2-rank interface forces differ"
    ;;
  tracked)
    command -v git > /dev/null && git -C "$repo" rev-parse > /dev/null 2>&1 || fail "needs the git checkout of the sources"
    rm -rf "$work" && mkdir -p "$work/src/cases/coupled"
    case_files=$(git -C "$repo" ls-files "cases/coupled/$name")
    [ -n "$case_files" ] || fail "no tracked files in cases/coupled/$name"
    (cd "$repo" && cp --parents $case_files "$work/src/") || fail "copy failed"
    ln -s "$build" "$work/src/build"
    cd "$work/src" || exit 1
    sums() { find . -path ./build -prune -o -type f -print0 | sort -z | xargs -0 sha256sum; }
    before=$(sums)
    cd "cases/coupled/$name" || exit 1
    # the source tree's own build/, nothing sourced
    clean ./Allrun "$end" > ../allrun.out 2>&1 || { cat ../allrun.out; fail "Allrun in the source tree failed"; }
    rm ../allrun.out
    reached . "$end"
    written=$(cd "$work/src" && find . -path ./build -prune -o -type f -print | sed 's|^\./||' | sort |
      comm -23 - <(echo "$case_files" | sort))
    [ -n "$written" ] || fail "Allrun wrote nothing?"
    not_ignored=$(cd "$repo" && echo "$written" | git check-ignore --no-index --verbose --non-matching --stdin | grep '^::' | cut -f2)
    [ -z "$not_ignored" ] || fail "Allrun output not ignored by git: $(echo $not_ignored | head -c 400)"
    hidden=$(git -C "$repo" ls-files -ci --exclude-standard -- cases/)
    [ -z "$hidden" ] || fail "tracked case files match .gitignore: $hidden"
    clean ./Allclean || fail "Allclean failed"
    cd "$work/src" || exit 1
    after=$(sums)
    [ "$before" = "$after" ] || { diff <(echo "$before") <(echo "$after"); fail "Allrun + Allclean changed the tracked files or left files behind"; }
    echo "$(echo "$written" | wc -l) files written and git-ignored; after Allclean the $(echo "$case_files" | wc -l) tracked files are as before and alone"
    ;;
  *) fail "unknown mode $mode" ;;
esac
echo "PASS $mode $name"
