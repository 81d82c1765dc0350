#pragma once
// The registry of mesh generators (`meshes.<name>.generator: {type: ..., ...}`): every generator is one
// entry {name, keys, description, generate}. The valid `type:` values (and their "did you mean") come from
// this table. Adding a generator = one file with its geometry and its reader + one line in
// GeneratorKinds.cpp (docs/ARCHITECTURE.md, "How to add a generator").

#include <array>
#include <string>
#include <vector>

#include "structure/model/Error.hpp"
#include "structure/model/MeshData.hpp"
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure {

struct GeneratorKind {
  std::string name;               ///< the generator's `type:`
  std::vector<std::string> keys;  ///< the keys of its entry (with `type`)
  std::string description;        ///< one line, for docs and messages
  /// Reads the entry (calling g.finish) and builds the mesh `meshName`; errors are located at the entry.
  MeshData (*generate)(const YamlMap& g, const std::string& meshName) = nullptr;
  /// The entry's declared keys (SceneSchema), when the generator has them (`parafoil`); `keys` are its names.
  /// The other generators' keys are not in the schema yet.
  const SchemaSection* schema = nullptr;
};

/// Every generator, in the order their names are listed in messages.
const std::vector<GeneratorKind>& generatorKinds();

/// Builds the mesh a `generator:` entry describes.
MeshData generateMesh(const YamlMap& g, const std::string& meshName);

// For the generators' readers.

/// A list of at least 2 points [x, y, z] under `key`, with located errors.
std::vector<std::array<double, 3>> readPoints(const YamlMap& g, const std::string& key);

/// Runs the generator `fn(params, name)`. Its messages name the parameter; this adds where in the scene the
/// entry is. YAML errors are already located and pass through unchanged.
template <class Params, class Fn>
MeshData locatedGenerate(const YamlMap& g, Fn fn, const Params& params, const std::string& name) {
  try {
    return fn(params, name);
  } catch (const InputError& e) {
    throw InputError(locate(g.file(), g.node(), g.path()) + ": " + e.what());
  }
}

}  // namespace fsi::structure
