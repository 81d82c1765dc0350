#pragma once
// The registry of mesh generators (`meshes.<name>.generator: {type: ..., ...}`): every generator is one
// entry {name, keys, description, generate}. The valid `type:` values (and their "did you mean") come from
// this table. Adding a generator = one file with its geometry and its reader + one line in
// GeneratorKinds.cpp (docs/ARCHITECTURE.md, "How to add a generator").

#include <string>
#include <vector>

#include "structure/model/MeshData.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure {

struct GeneratorKind {
  std::string name;               ///< the generator's `type:`
  std::vector<std::string> keys;  ///< the keys of its entry (with `type`)
  std::string description;        ///< one line, for docs and messages
  /// Reads the entry (calling g.finish) and builds the mesh `meshName`; errors are located at the entry.
  MeshData (*generate)(const YamlMap& g, const std::string& meshName) = nullptr;
};

/// Every generator, in the order their names are listed in messages.
const std::vector<GeneratorKind>& generatorKinds();

/// Builds the mesh a `generator:` entry describes.
MeshData generateMesh(const YamlMap& g, const std::string& meshName);

}  // namespace fsi::structure
