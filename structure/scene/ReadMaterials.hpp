#pragma once
// The scene's `materials:` section: membrane and cable materials by name.

#include <map>
#include <string>
#include <vector>

#include "structure/model/Model.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure {

struct MaterialTable {
  std::map<std::string, int> membraneIdx, cableIdx;  ///< name -> index into the lists below
  std::vector<MembraneMaterial> membraneMats;
  std::vector<CableMaterial> cableMats;
};

/// Reads `materials:` of the top-level map `top`.
MaterialTable readMaterials(const YamlMap& top);

/// The index of the material `m[key]` names in `idx` (of the given kind, for the message).
int materialRef(const YamlMap& m, const std::string& key, const std::map<std::string, int>& idx,
                const std::string& kind);

}  // namespace fsi::structure
