#!/bin/sh
# Found by the fuzz test (coordinate mutations nan / inf in MSH 4.1 ASCII and in polyMesh/points). Both
# readers accept non-finite coordinates:
#   map-check prints "tolerance nan (absolute)" / "tolerance inf" and exits 1 ("points do not map"), its
#   JSON has nulls; a `fsi run` of the same Gmsh file stops with "triangle 25 of mesh 'sheet' is degenerate"
#   (exit 2, neither file nor line).
# Expected: exit 2 naming the file and line (mesh.msh:32, foam/constant/polyMesh/points:52).
FSI=${1:-build/bin/fsi}; D=$(dirname "$0"); REF=$D/../../seeds/gmsh/square-4.1-ascii.msh
OUT=${TMPDIR:-/tmp}/fsi-found-map-check.txt
"$FSI" map-check "$D/mesh.msh" "$REF" > "$OUT"; rc=$?; sed -n 3p "$OUT"; echo "exit $rc"
"$FSI" map-check "$D/foam:top" "$REF" > "$OUT"; rc=$?; sed -n 3p "$OUT"; echo "exit $rc"
