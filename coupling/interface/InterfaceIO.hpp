#pragma once
// InterfaceIO: reads an interface mesh from a Gmsh file (the structure side) or from a boundary patch of an
// OpenFOAM case (the fluid side). Only the points used by the kept faces are returned, renumbered in order of
// first use. All problems are fsi::InputError naming the file and, where it applies, the line or entry.

#include <filesystem>
#include <string>
#include <vector>

#include "coupling/interface/InterfaceMesh.hpp"

namespace fsi::coupling {

/// Reads `spec`, one of
///   FILE.msh          every triangle of a Gmsh file (quadrangles arrive split in two by readGmsh)
///   FILE.msh:GROUP    the triangles of one physical surface group ("physical_2_<tag>" when unnamed)
///   CASE_DIR:PATCH    one boundary patch of an OpenFOAM case (faces kept as polygons)
/// The mesh is named `spec`.
InterfaceMesh readInterface(const std::string& spec);

/// Triangles of a Gmsh file, all of them (empty `group`) or those of one physical surface group.
InterfaceMesh readGmshInterface(const std::filesystem::path& file, const std::string& group = "");

/// Patch `patch` of CASE_DIR/constant/polyMesh/{points,faces,boundary}, ASCII FoamFile format only (binary
/// and compressed files are reported with the conversion to run). Faces keep OpenFOAM's orientation (normal
/// out of the fluid domain).
InterfaceMesh readOpenFoamPatch(const std::filesystem::path& caseDir, const std::string& patch);

/// An ASCII STL file as an interface mesh: vertices with the same coordinates merged, every facet a triangle
/// turned to face the other way, so that the mesh has the fluid side's orientation (an STL's facets face out
/// of the body, an OpenFOAM patch's into it); writeInterfaceStl turns them back. The undeformed skin a
/// remeshed run moves and writes. Binary STL and malformed lines are fsi::InputError naming the file and
/// line.
InterfaceMesh readStlSurface(const std::filesystem::path& file);

/// Writes `mesh` moved by `displacement` (3 per point; empty: unmoved) as an ASCII STL solid named after the
/// mesh: each polygon as the fan of triangles about its vertex average, turned to face the other way
/// (OpenFOAM's patch normals point out of the fluid, into the body; an STL's point out of the body). The
/// surface a new fluid mesh is snapped to when a run is remeshed. Throws std::runtime_error naming the file
/// when it cannot be written, std::invalid_argument for a displacement of the wrong size.
void writeInterfaceStl(const InterfaceMesh& mesh, const std::vector<double>& displacement,
                       const std::filesystem::path& file);

}  // namespace fsi::coupling
