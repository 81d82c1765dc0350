#!/usr/bin/env bash
# bench/adapter-scale (issue 16): the generator refuses bad arguments with a clear message; a tiny case
# (about 1000 interface points, 2 windows) runs serial and on 2 ranks, and collect.py reads both runs.
# Checks against what the case must be, not against earlier output: the patch of n x n faces has (n + 1)^2
# points, the cross-pattern structure of m x m squares 2 m^2 + 2 m + 1 nodes, the run did the windows it was
# asked for on the ranks it was asked for, and the transfer's timed parts do not add up to more than the
# transfer (a timer counted twice or outside the transfer would).
# Usage: adapter_scale_test.sh BUILD_DIR WORK_DIR
set -uo pipefail
build=$1 work=$2
src=$(cd "$(dirname "$0")/../.." && pwd)
gen=$src/bench/adapter-scale/make_case.py
fail=0
bad() { echo "FAIL: $*" >&2; fail=1; }
rm -rf "$work" && mkdir -p "$work"

# expect_error MESSAGE ARGS...: make_case.py ARGS must exit non-zero with MESSAGE on stderr
expect_error() {
  local want=$1 out
  shift
  if out=$("$gen" "$@" 2>&1); then bad "make_case.py $* succeeded"; return; fi
  grep -qF -- "$want" <<< "$out" || bad "make_case.py $*: expected '$want', got: $out"
}
expect_error "N must be a whole number, not 'abc'" abc 1 "$work/x"
expect_error "N must be a whole number in [100, 4000000], got 50" 50 1 "$work/x"
expect_error "RANKS must be a whole number in [1, 4], got 8" 1000 8 "$work/x"
expect_error "RANKS must be 1, 2 or 4, got 3" 1000 3 "$work/x"
expect_error "--windows must be a whole number in [1, 100], got 0" 1000 1 "$work/x" --windows 0
expect_error "--threads must be a whole number in [1, 64], got 0" 1000 1 "$work/x" --threads 0
# --threads reaches the structure's scene (the solver's threads on the master rank)
"$gen" 1000 1 "$work/threads" --threads 2 > /dev/null || bad "make_case.py --threads 2 failed"
grep -qx "solver: {threads: 2}" "$work/threads/structure.yaml" 2>/dev/null || bad "--threads 2: no 'solver: {threads: 2}' in structure.yaml"
mkdir -p "$work/exists"
expect_error "exists; remove it or choose another folder" 1000 1 "$work/exists"

. "$build/share/fsi/fsi-env.sh" || exit 1
export FSI_SCALE_DIR=$work/runs
for ranks in 1 2; do
  "$src/bench/adapter-scale/run.sh" 1000 "$ranks" 2 > "$work/run-np$ranks.log" 2>&1 || { bad "run.sh 1000 $ranks failed: $(tail -5 "$work/run-np$ranks.log")"; continue; }
done
/usr/bin/python3 "$src/bench/adapter-scale/collect.py" "$work/runs" --json "$work/runs.json" > "$work/table.md" || bad "collect.py failed"
/usr/bin/python3 - "$work/runs.json" <<'PY' || fail=1
import json, math, sys
runs = json.load(open(sys.argv[1]))
ok = True
def check(cond, what):
    global ok
    if not cond:
        print("FAIL:", what, file=sys.stderr)
        ok = False
check(sorted(r["ranks"] for r in runs) == [1, 2], f"ranks {[r['ranks'] for r in runs]}, expected 1 and 2")
for r in runs:
    n = round(math.sqrt(1000)) - 1   # the generator's rule
    m = round(0.7 * n)
    check(r["points"] == (n + 1) ** 2, f"{r['case']}: {r['points']} fluid points, expected (n+1)^2 = {(n + 1) ** 2}")
    check(r["nodes"] == 2 * m * m + 2 * m + 1, f"{r['case']}: {r['nodes']} structure nodes, expected {2 * m * m + 2 * m + 1}")
    check(r["windows"] == 2, f"{r['case']}: {r['windows']} windows, expected 2")
    parts = r["gather"] + r["scatter"] + r["load_projection"] + r["disp_projection"]
    check(min(r["gather"], r["scatter"], r["load_projection"], r["disp_projection"]) >= 0, f"{r['case']}: a negative part")
    check(parts <= r["transfer"], f"{r['case']}: transfer parts {parts} s > transfer {r['transfer']} s")
    check(0 < r["serial_fraction"] < 1, f"{r['case']}: serial fraction {r['serial_fraction']}")
sys.exit(0 if ok else 1)
PY
[ "$fail" = 0 ] && echo "adapter-scale: all checks passed" && cat "$work/table.md"
exit $fail
