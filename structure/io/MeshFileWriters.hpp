#pragma once
// Writes a MeshData for inspection in Gmsh/ParaView and for meshing the flow around it:
//  - Gmsh MSH 2.2 (ASCII) with every named group as a physical group: triangles (physical surfaces), lines
//    (physical curves) and node groups (physical points, one point element per node). An element that
//    belongs to several groups is written once per group, as Gmsh does; elements with the same set of groups
//    share one elementary entity, so that reading the file back (readGmsh, or Gmsh) gives the same groups.
//  - STL (ASCII) of a set of triangles with their outward normals: the surface snappyHexMesh cuts the fluid
//    mesh around.
// Both are written through io/AtomicFile (temporary file, fsync, rename): a failed write leaves no half file.

#include <array>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "structure/model/MeshData.hpp"

namespace fsi::structure {

/// Writes `mesh` as MSH 2.2 ASCII. Throws std::runtime_error naming the file when it cannot be written.
void writeMsh(const MeshData& mesh, const std::filesystem::path& file);

/// Writes the triangles `triangles` (indices into mesh.triangles; all when empty) as an ASCII STL solid named
/// `solid`. Throws std::runtime_error naming the file when it cannot be written.
/// One ASCII STL facet a, b, c (its normal from the vertex order, counter-clockwise; zero for a degenerate
/// one), at full double precision: the facet writer of writeStl and of the coupling's interface skins.
void writeStlFacet(std::ostream& out, const std::array<double, 3>& a, const std::array<double, 3>& b,
                   const std::array<double, 3>& c);

void writeStl(const MeshData& mesh, const std::vector<int>& triangles, const std::filesystem::path& file,
              const std::string& solid);

}  // namespace fsi::structure
