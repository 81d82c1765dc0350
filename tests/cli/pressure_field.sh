#!/bin/bash
# fsi run on a scene with `pressure_field` (tests/data/pressure-field-plate.yaml: a VTK surface mapped by the
# conservative projection as a dead load, and a CSV Cp cloud as a follower load): the effect is registered in
# the fsi program, its files are found relative to the scene's folder (not the working directory), the run
# does work on the film; a broken or missing file stops with exit code 2 and a message naming the scene entry,
# the file and the line.
set -u
FSI=$1
WORK=$2
SRC=$(cd "$(dirname "$0")/../data" && pwd)
rm -rf "$WORK" && mkdir -p "$WORK" && cd "$WORK" || exit 1
fail() { echo "FAIL: $*"; exit 1; }

"$FSI" run "$SRC/pressure-field-plate.yaml" --out run > run.log 2>&1 || { cat run.log; fail "fsi run failed"; }
cat run.log
/usr/bin/python3 - run/summary.json <<'PY' || fail "summary.json"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["stop_reason"] == "end_time", s["stop_reason"]
assert "pressure_field" in s["effects"], s["effects"]
w = s["stats"]["external_work"]
assert w > 0, w  # the loads did work on the film
print("external work", w)
PY

# A copy with a broken cloud (a non-number on line 5) and one with a missing surface file.
cp -r "$SRC/pressure-field" "$SRC/pressure-field-plate.yaml" .
sed -i '5s/.*/0.1,0.2,0,abc/' pressure-field/cloud.csv
"$FSI" run pressure-field-plate.yaml --out bad > bad.log 2>&1
rc=$?
cat bad.log
[ $rc -eq 2 ] || fail "broken cloud: exit code $rc, expected 2"
grep -q "pressure-field-plate.yaml:16:.*effects.pressure_field\[1\].file" bad.log || fail "the scene entry is not named"
grep -q "cloud.csv:5: column 'cp': 'abc' is not a finite number" bad.log || fail "file, line and column not named"

rm pressure-field/surface.vtk
"$FSI" run pressure-field-plate.yaml --out missing > missing.log 2>&1
rc=$?
cat missing.log
[ $rc -eq 2 ] || fail "missing surface: exit code $rc, expected 2"
grep -q "pressure-field-plate.yaml:13:.*surface.vtk: no such file" missing.log || fail "missing file not located"
echo "OK"
