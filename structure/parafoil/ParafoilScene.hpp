#pragma once
// The `parafoil` generator entry of a scene (meshes.NAME.generator with type: parafoil): reads and checks its
// keys into ParafoilParams through the generator's schema section (key names, types, defaults, ranges:
// parafoilSchema(), listed in docs/SCENES.md's key reference); a section file is read relative to the scene's
// folder.

#include <filesystem>
#include <string>
#include <vector>

#include "structure/parafoil/ParafoilGeometry.hpp"
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure::parafoil {

/// The generator entry's keys: the one list the reader reads through and the docs are made from.
const SchemaSection& parafoilSchema();

/// Every key the generator entry may hold (parafoilSchema()'s names).
const std::vector<std::string>& parafoilKeys();

/// Reads the generator entry `g` (all keys but `type` optional); errors are located at the key.
ParafoilParams readParafoilParams(const YamlMap& g, const std::filesystem::path& sceneDir);

}  // namespace fsi::structure::parafoil
