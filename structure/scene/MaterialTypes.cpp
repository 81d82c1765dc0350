#include "structure/scene/MaterialTypes.hpp"

#include <cmath>

#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure {

namespace {

int readMembrane(const YamlMap& m, const std::string& name, const std::vector<std::string>& validKeys,
                 MaterialTable& table) {
  MembraneMaterial mm;
  mm.name = name;
  // Every positive quantity under one rule (isPositiveNormal): a subnormal thickness or density (1e-320)
  // would make the lumped masses underflow to 0.
  mm.young = m.positive("young");
  mm.poisson = m.number("poisson");
  mm.thickness = m.positive("thickness");
  mm.density = m.positive("density");
  mm.wrinkling = m.boolean("wrinkling", true);
  m.finish(validKeys);
  if (!(mm.poisson >= 0 && mm.poisson < 0.5)) m.failAt("poisson", "must be in [0, 0.5)");
  table.membrane.push_back(mm);
  return int(table.membrane.size()) - 1;
}

int readCable(const YamlMap& m, const std::string& name, const std::vector<std::string>& validKeys,
              MaterialTable& table) {
  CableMaterial cm;
  cm.name = name;
  cm.young = m.positive("young");
  cm.area = m.positive("area");
  cm.density = m.positive("density");
  m.finish(validKeys);
  table.cable.push_back(cm);
  return int(table.cable.size()) - 1;
}

int readPointMass(const YamlMap& m, const std::string& name, const std::vector<std::string>& validKeys,
                  MaterialTable& table) {
  PointMassMaterial pm;
  pm.name = name;
  pm.mass = m.positive("mass");  // not subnormal: 1/m would overflow to inf in the step loop
  m.finish(validKeys);
  table.pointMass.push_back(pm);
  return int(table.pointMass.size()) - 1;
}

// A material of a kind without a list of its own in the table (MaterialTable::other): every key a positive
// number, the kind's build checks and uses them.
int readKindMaterial(const YamlMap& m, const std::string& name, const std::vector<std::string>& validKeys,
                     MaterialTable& table, const std::string& kind) {
  KindMaterial km;
  km.name = name;
  for (const std::string& key : validKeys)
    if (key != "type") km.values[key] = m.positive(key);
  m.finish(validKeys);
  auto& list = table.other[kind];
  list.push_back(km);
  return int(list.size()) - 1;
}

int readBar(const YamlMap& m, const std::string& name, const std::vector<std::string>& validKeys,
            MaterialTable& table) {
  return readKindMaterial(m, name, validKeys, table, "bar");
}

}  // namespace

const std::vector<MaterialType>& materialTypes() {
  // One line per material type.
  static const std::vector<MaterialType> types{
      {"membrane", "membrane", {"young", "poisson", "thickness", "density", "wrinkling"}, readMembrane},
      {"cable", "cable", {"young", "area", "density"}, readCable},
      {"point_mass", "point_mass", {"mass"}, readPointMass},
      {"bar", "bar", {"young", "area", "density"}, readBar},
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
    for (const MaterialType& t : materialTypes()) {
      if (t.name != type) continue;
      std::vector<std::string> valid{"type"};
      valid.insert(valid.end(), t.keys.begin(), t.keys.end());
      table.index[t.elementKind][name] = t.read(m, name, valid, table);
    }
  }
  return table;
}

}  // namespace fsi::structure
