#pragma once
// The scene's `materials:` section, read through the material-type registry
// (structure/scene/MaterialTypes: valid types, their keys and checks), and the references to materials
// from the meshes.

#include <map>
#include <string>

#include "structure/scene/MaterialTypes.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure {

/// Reads `materials:` of the top-level map `top`.
MaterialTable readSceneMaterials(const YamlMap& top);

/// Name -> index of the materials that feed the element kind `kind` (empty when the scene has none).
const std::map<std::string, int>& materialsOfKind(const MaterialTable& table, const std::string& kind);

/// The index of the material `m[key]` names in `idx` (of the given kind, for the message).
int materialRef(const YamlMap& m, const std::string& key, const std::map<std::string, int>& idx,
                const std::string& kind);

}  // namespace fsi::structure
