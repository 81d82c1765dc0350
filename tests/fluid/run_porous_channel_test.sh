#!/usr/bin/env bash
# ctest fluid.porous-channel: cases/fluid/porous-channel copied out of the source tree and run by its Allrun
# (four through-flow speeds, about 10 s): the through-flow is the inflow, the pressure drop is the
# Darcy-Forchheimer law, and a, b fitted back are the inputs (the case's own checks, exit 1 naming a failure);
# then the case's outputs are there. Exit 77 (skipped) without Debian's OpenFOAM.
# Usage: run_porous_channel_test.sh SOURCE_DIR WORK_DIR
set -u
src=$1/cases/fluid/porous-channel
work=$2
fail() { echo "FAIL: $*" >&2; exit 1; }
command -v pimpleFoam > /dev/null && command -v createBaffles > /dev/null || { echo "no OpenFOAM: skipped"; exit 77; }
rm -rf "$work" && mkdir -p "$(dirname "$work")" && cp -r "$src" "$work" || fail "copying the case"
"$work/Allrun" || fail "Allrun failed (its checks above)"
for f in summary.json porous_channel.png log.Allrun runs/u_0.5/u_0.5.foam; do
  [ -s "$work/$f" ] || [ -e "$work/$f" ] || fail "Allrun did not write $f"
done
/usr/bin/python3 - "$work/summary.json" <<'PY' || fail "summary.json"
import json, sys
s = json.load(open(sys.argv[1]))
assert not s["failures"], s["failures"]
assert len(s["points"]) == 4, "four speeds"
assert s["openfoam"] == {"D": s["a_per_m"], "I": 2 * s["b"], "length": 1.0}
PY
"$work/Allclean" && [ ! -e "$work/runs" ] || fail "Allclean left runs/"
echo "fluid.porous-channel: passed"
