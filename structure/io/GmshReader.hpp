#pragma once
// Reads a Gmsh mesh file (MSH 2.2 or 4.1, ASCII or binary) into MeshData through the Gmsh API.

#include <filesystem>
#include <string>

#include "structure/model/MeshData.hpp"

namespace fsi::structure {

/// Reads `file` and returns it as MeshData named `meshName`.
///
/// Kept elements: 2-node lines (cables), 3-node triangles and 4-node quadrangles (membranes; each quad is
/// split into two triangles along its shorter diagonal, both keeping the quad's orientation and tag).
/// Points are ignored; any other element type is an error. Only nodes used by kept elements become
/// points. Physical groups become named groups ("physical_<dim>_<tag>" when unnamed): surface groups fill
/// triangleGroups and nodeGroups, curve groups lineGroups and nodeGroups, point groups nodeGroups.
/// Elements with the same node sequence are read once (MSH 2.2 repeats an element for every physical
/// group of its entity); the first copy's tag is kept.
///
/// Throws fsi::InputError (naming the file) for a missing or unreadable file, unsupported elements, or a
/// file without lines or triangles. Opens its own Gmsh session: must not be called while the caller has
/// a Gmsh session open (the Gmsh API is global state). Calls from several threads are serialised.
MeshData readGmsh(const std::filesystem::path& file, const std::string& meshName);

}  // namespace fsi::structure
