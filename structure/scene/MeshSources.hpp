#pragma once
// Turns a scene's `meshes.<name>` entry into MeshData: a Gmsh file (`file:`) or a built-in generator
// (`generator: {type: ..., ...}`, one of generatorKinds() in GeneratorKinds.hpp).

#include <filesystem>
#include <string>

#include "structure/model/MeshData.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure {

/// Reads the `file` or `generator` key of a mesh entry (and only those keys).
MeshData meshFromScene(const YamlMap& entry, const std::string& name, const std::filesystem::path& sceneDir);

}  // namespace fsi::structure
