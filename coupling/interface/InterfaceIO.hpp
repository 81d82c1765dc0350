#pragma once
// InterfaceIO: reads an interface mesh from a Gmsh file (the structure side) or from a boundary patch of an
// OpenFOAM case (the fluid side). Only the points used by the kept faces are returned, renumbered in order of
// first use. All problems are fsi::InputError naming the file and, where it applies, the line or entry.

#include <filesystem>
#include <string>

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

}  // namespace fsi::coupling
