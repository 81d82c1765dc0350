#pragma once
// Reads a Gmsh mesh file (MSH 2.2 or 4.1, ASCII or binary) into MeshData, with the project's own MSH reader
// (MshReader: checked against hostile input, never runs scripts; the Gmsh library is not used).

#include <filesystem>
#include <string>

#include "structure/model/MeshData.hpp"

namespace fsi::structure {

/// Reads `file` and returns it as MeshData named `meshName`.
///
/// Kept elements: 2-node lines (cables), 3-node triangles and 4-node quadrangles (membranes; each quad is
/// split into two triangles along its shorter diagonal, both keeping the quad's orientation and tag).
/// Points are ignored; any other element type is an error. Only nodes used by kept elements become
/// points, in ascending tag order. Elements are ordered by entity (dimension, then tag), triangles before
/// quadrangles, file order otherwise. Physical groups become named groups ("physical_<dim>_<tag>" when
/// unnamed): surface groups fill triangleGroups and nodeGroups, curve groups lineGroups and nodeGroups,
/// point groups nodeGroups. Elements with the same node sequence are read once (MSH 2.2 repeats an element
/// for every physical group of its entity); the first copy's tag is kept.
///
/// Throws fsi::InputError, and nothing else, for any problem: naming the file and, for a malformed file,
/// the line (ASCII) or byte offset (binary) and the section. A Gmsh script (.geo) is refused with the
/// command that meshes it. Thread-safe (no global state).
MeshData readGmsh(const std::filesystem::path& file, const std::string& meshName);

}  // namespace fsi::structure
