#include "structure/scene/MaterialTypes.hpp"

#include "structure/model/MaterialKeys.hpp"
#include "structure/scene/SceneSchema.hpp"

namespace fsi::structure {

namespace {

// Each reader reads through its type's schema section (model/MaterialKeys): the ranges and their messages are
// the keys' entries, located at the key. Every positive quantity is under one rule (isPositiveNormal): a
// subnormal thickness or density (1e-320) would make the lumped masses underflow to 0.
int readMembrane(const YamlMap& entry, const std::string& name, MaterialTable& table) {
  const SchemaMap m(entry, membraneMaterialKeys());
  MembraneMaterial mm;
  mm.name = name;
  mm.young = m.number("young");
  mm.poisson = m.number("poisson");
  mm.thickness = m.number("thickness");
  mm.density = m.number("density");
  mm.wrinkling = m.boolean("wrinkling");
  m.finish();
  table.membrane.push_back(mm);
  return int(table.membrane.size()) - 1;
}

int readCable(const YamlMap& entry, const std::string& name, MaterialTable& table) {
  const SchemaMap m(entry, cableMaterialKeys());
  CableMaterial cm;
  cm.name = name;
  cm.young = m.number("young");
  cm.area = m.number("area");
  cm.density = m.number("density");
  m.finish();
  table.cable.push_back(cm);
  return int(table.cable.size()) - 1;
}

int readPointMass(const YamlMap& entry, const std::string& name, MaterialTable& table) {
  const SchemaMap m(entry, pointMassMaterialKeys());
  PointMassMaterial pm;
  pm.name = name;
  pm.mass = m.number("mass");  // not subnormal: 1/m would overflow to inf in the step loop
  m.finish();
  table.pointMass.push_back(pm);
  return int(table.pointMass.size()) - 1;
}

// A bar material (`type: bar`, the `bar` element kind): a list of its own in MaterialTable::other["bar"]
// (the kind's build reads the values by name), the keys and ranges in its schema section.
const SchemaSection& barMaterialKeys() {
  static const SchemaSection s{
      "materials.NAME (type: bar)",
      "a 2-node linear elastic bar: tension and compression (`bars:` of a mesh)",
      {{"type", KeyType::Choice, "", "", "required", {}, {}, {"bar"}, "the material type"},
       {"young", KeyType::Number, "Pa", "", "required", KeyBound{0, false}, {}, {}, "Young's modulus E"},
       {"area", KeyType::Number, "m²", "", "required", KeyBound{0, false}, {}, {}, "cross-section A"},
       {"density", KeyType::Number, "kg/m³", "", "required", KeyBound{0, false}, {}, {}, "mass density ρ"}}};
  return s;
}

int readBar(const YamlMap& entry, const std::string& name, MaterialTable& table) {
  const SchemaMap m(entry, barMaterialKeys());
  KindMaterial km;
  km.name = name;
  for (const char* key : {"young", "area", "density"}) km.values[key] = m.number(key);
  m.finish();
  auto& list = table.other["bar"];
  list.push_back(km);
  return int(list.size()) - 1;
}

}  // namespace

const std::vector<MaterialType>& materialTypes() {
  // One line per material type.
  static const std::vector<MaterialType> types{
      {"membrane", "membrane", &membraneMaterialKeys(), readMembrane},
      {"cable", "cable", &cableMaterialKeys(), readCable},
      {"point_mass", "point_mass", &pointMassMaterialKeys(), readPointMass},
      {"bar", "bar", &barMaterialKeys(), readBar},
  };
  return types;
}

MaterialTable readMaterials(const YamlMap& materials) {
  MaterialTable table;
  std::vector<std::string> names;
  for (const MaterialType& t : materialTypes()) names.push_back(t.name);
  for (const auto& name : materials.keys()) {
    YamlMap m = materials.map(name);
    const std::string type = m.choice("type", names);
    for (const MaterialType& t : materialTypes())
      if (t.name == type) table.index[t.elementKind][name] = t.read(m, name, table);
  }
  return table;
}

}  // namespace fsi::structure
