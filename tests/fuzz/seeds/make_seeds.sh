#!/bin/sh
# Regenerates the fuzz test's mesh seeds (committed, so the test needs neither gmsh nor blockMesh):
#   gmsh/square-{2.2,4.1}-{ascii,binary}.msh  unit square in z = 0, 26 triangles, groups sheet/rim/corner
#   gmsh/quad-4.1-ascii.msh                   the same square as 2x2 quadrangles
#   openfoam/constant/polyMesh                blockMesh of a 1 x 1 x 0.25 box, 3x3x1 cells; patch `top`
#                                             is the square z = 0 (the Gmsh seeds' surface)
# Usage: tests/fuzz/seeds/make_seeds.sh  (needs gmsh and Debian's OpenFOAM blockMesh)
set -e
cd "$(dirname "$0")"
for v in 2.2 4.1; do
  gmsh -2 gmsh/square.geo -setnumber Mesh.MshFileVersion $v -setnumber Mesh.Binary 0 -o gmsh/square-$v-ascii.msh >/dev/null
  gmsh -2 gmsh/square.geo -setnumber Mesh.MshFileVersion $v -setnumber Mesh.Binary 1 -o gmsh/square-$v-binary.msh >/dev/null
done
gmsh -2 gmsh/quad.geo -setnumber Mesh.MshFileVersion 4.1 -o gmsh/quad-4.1-ascii.msh >/dev/null
(cd openfoam && WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam} blockMesh >/dev/null && rm -rf constant/polyMesh/sets)
ls -l gmsh/*.msh openfoam/constant/polyMesh
