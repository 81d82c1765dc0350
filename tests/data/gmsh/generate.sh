#!/bin/sh
# Regenerates the Gmsh fixtures of tests/unit/test_gmsh_reader.cpp, test_projection.cpp and test_scene_interface.cpp from the .geo
# files here with the gmsh command (Gmsh 4.8.4 wrote the committed files). The tests check them against
# properties of the geometry (counts of the structured meshes, areas, lengths, normals), not against the
# output of a reader.
set -e
cd "$(dirname "$0")"
for geo in rectangle quads two_groups box; do
  gmsh -2 $geo.geo -format msh41 -o ${geo}_41.msh > /dev/null
  gmsh -2 $geo.geo -format msh22 -o ${geo}_22.msh > /dev/null
done
for geo in rectangle box; do
  gmsh -2 $geo.geo -format msh41 -bin -o ${geo}_41_binary.msh > /dev/null
  gmsh -2 $geo.geo -format msh22 -bin -o ${geo}_22_binary.msh > /dev/null
done
gmsh -2 second_order.geo -format msh41 -o second_order_41.msh > /dev/null
gmsh -2 two_surfaces.geo -format msh41 -o two_surfaces_41.msh > /dev/null
gmsh -2 unstructured_square.geo -format msh41 -o unstructured_square_41.msh > /dev/null
gmsh -1 cable.geo -format msh41 -o cable_41.msh > /dev/null
gmsh -1 cable.geo -format msh22 -o cable_22.msh > /dev/null
