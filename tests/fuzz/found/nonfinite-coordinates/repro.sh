#!/bin/sh
# Found by the fuzz test (coordinate mutations nan / inf / 1e308 in MSH 4.1 ASCII, MSH binary and in
# polyMesh/points). Both readers accept non-finite coordinates, and map-check computes with whatever comes:
#   mesh.msh        (node `1 1 inf`, line 32)        map-check: "tolerance inf (absolute)", exit 1
#   foam:top        (points:52 `(1 1 nan)`)          map-check: "tolerance nan (absolute)", exit 1, JSON nulls
#   huge.msh        (line 66 `1e308 0.5 0`, finite)  map-check: "tolerance inf", "all points mapped", exit 0,
#                                                    JSON with null tolerance and errors
# a `fsi run` of mesh.msh stops with "triangle 25 of mesh 'sheet' is degenerate" (exit 2, no file, no line).
# Expected: exit 2 naming the file and line (mesh.msh:32, foam/constant/polyMesh/points:52) for non-finite
# values; for finite-but-absurd ones at least no "all points mapped" with an infinite tolerance.
FSI=${1:-build/bin/fsi}; D=$(dirname "$0"); REF=$D/../../seeds/gmsh/square-4.1-ascii.msh
OUT=${TMPDIR:-/tmp}/fsi-found-map-check.txt
"$FSI" map-check "$D/mesh.msh" "$REF" > "$OUT"; rc=$?; sed -n 3p "$OUT"; echo "exit $rc"
"$FSI" map-check "$D/foam:top" "$REF" > "$OUT"; rc=$?; sed -n 3p "$OUT"; echo "exit $rc"
"$FSI" map-check "$REF" "$D/huge.msh" > "$OUT"; rc=$?; sed -n 3p "$OUT"; tail -1 "$OUT"; echo "exit $rc"
