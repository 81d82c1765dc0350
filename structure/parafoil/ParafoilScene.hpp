#pragma once
// The `parafoil` generator entry of a scene (meshes.NAME.generator with type: parafoil): reads and checks its
// keys into ParafoilParams. Key names and defaults are listed in docs/SCENES.md; a section file is read
// relative to the scene's folder.

#include <filesystem>
#include <string>
#include <vector>

#include "structure/parafoil/ParafoilGeometry.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure::parafoil {

/// Every key the generator entry may hold (for "did you mean" and the docs).
const std::vector<std::string>& parafoilKeys();

/// Reads the generator entry `g` (all keys but `type` optional); errors are located at the key.
ParafoilParams readParafoilParams(const YamlMap& g, const std::filesystem::path& sceneDir);

}  // namespace fsi::structure::parafoil
