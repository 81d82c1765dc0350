#!/bin/sh
# Found by the fuzz test (OpenFOAM number mutations 1e400, 2^64). The polyMesh reader's integer() and number()
# (coupling/interface/InterfaceIO.cpp) check only from_chars' end pointer, not its error code: a number out
# of range keeps the initial value 0 and is accepted.
#   coordinate/  points:52 `(1 1 1e400)` is read as (1 1 0): map-check exits 0, "all points mapped"
#   label/       faces:33 `4(18446744073709551632 17 21 20)` uses point 0: exit 1, a silently different
#                patch (points at z = -0.125 "do not map")
# Expected: exit 2, "points:52: number out of range" / "faces:33: point label out of range".
FSI=${1:-build/bin/fsi}; D=$(dirname "$0"); REF=$D/../../seeds/gmsh/square-4.1-ascii.msh
OUT=${TMPDIR:-/tmp}/fsi-found-map-check.txt
"$FSI" map-check "$D/coordinate:top" "$REF" > "$OUT"; rc=$?; tail -1 "$OUT"; echo "exit $rc"
"$FSI" map-check "$D/label:top" "$REF" > "$OUT"; rc=$?; tail -1 "$OUT"; echo "exit $rc"
