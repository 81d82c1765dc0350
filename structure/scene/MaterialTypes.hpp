#pragma once
// The registry of material types: the `type:` values of the scene's `materials:` entries. Each type has its
// name, its schema section (valid keys, types, ranges), a reader that parses and validates an entry (errors
// name file, line and key), and the element kind whose elements it feeds; meshes refer to a material through
// that kind's mesh key (`material` for membranes, `cable_material` for cables, `point_masses: {NODE_GROUP:
// MATERIAL}` for point masses). The scene's materials block reads through readMaterials(), so valid types and
// keys (and the "did you mean" of a misspelt one) come from here.

#include <map>
#include <string>
#include <vector>

#include "structure/model/Materials.hpp"
#include "structure/model/SchemaKey.hpp"

namespace fsi::structure {

class YamlMap;

struct MaterialType {
  std::string name;             ///< the `type:` value
  std::string elementKind;      ///< the element kind it feeds (ElementKind::name())
  const SchemaSection* schema;  ///< its keys (`type` first) with types, units, ranges (model/MaterialKeys)
  /// Parses one entry through `schema` (SchemaMap: unknown keys with "did you mean", values checked against
  /// their entries, errors naming file, line and key) and appends it to the table; returns its index in the
  /// kind's list.
  int (*read)(const YamlMap& entry, const std::string& name, MaterialTable& table);
};

/// Every registered material type, in registration order.
const std::vector<MaterialType>& materialTypes();

/// Reads a scene's `materials:` mapping through the registry.
MaterialTable readMaterials(const YamlMap& materials);

}  // namespace fsi::structure
