#include "structure/material/MaterialTypes.hpp"

#include <cmath>

#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure {

namespace {

// A density the lumped masses can hold: a subnormal one would make them underflow to 0.
void checkDensity(const YamlMap& m, double density) {
  if (!(density > 0) || !std::isnormal(density))
    m.failAt("density",
             "must be > 0 and at least 2.2e-308 (a smaller, subnormal density makes the lumped masses "
             "underflow to 0)");
}

int readMembrane(const YamlMap& m, const std::string& name, const std::vector<std::string>& validKeys,
                 MaterialTable& table) {
  MembraneMaterial mm;
  mm.name = name;
  mm.young = m.number("young");
  mm.poisson = m.number("poisson");
  mm.thickness = m.number("thickness");
  mm.density = m.number("density");
  mm.wrinkling = m.boolean("wrinkling", true);
  m.finish(validKeys);
  if (!(mm.young > 0)) m.failAt("young", "must be > 0");
  if (!(mm.poisson >= 0 && mm.poisson < 0.5)) m.failAt("poisson", "must be in [0, 0.5)");
  if (!(mm.thickness > 0)) m.failAt("thickness", "must be > 0");
  checkDensity(m, mm.density);
  table.membrane.push_back(mm);
  return int(table.membrane.size()) - 1;
}

int readCable(const YamlMap& m, const std::string& name, const std::vector<std::string>& validKeys,
              MaterialTable& table) {
  CableMaterial cm;
  cm.name = name;
  cm.young = m.number("young");
  cm.area = m.number("area");
  cm.density = m.number("density");
  m.finish(validKeys);
  if (!(cm.young > 0)) m.failAt("young", "must be > 0");
  if (!(cm.area > 0)) m.failAt("area", "must be > 0");
  checkDensity(m, cm.density);
  table.cable.push_back(cm);
  return int(table.cable.size()) - 1;
}

int readPointMass(const YamlMap& m, const std::string& name, const std::vector<std::string>& validKeys,
                  MaterialTable& table) {
  PointMassMaterial pm;
  pm.name = name;
  pm.mass = m.number("mass");
  m.finish(validKeys);
  // Normal, not just > 0: a subnormal mass would make 1/m overflow to inf in the step loop.
  if (!(pm.mass > 0) || !std::isnormal(pm.mass)) m.failAt("mass", "must be a finite number > 0 [kg]");
  table.pointMass.push_back(pm);
  return int(table.pointMass.size()) - 1;
}

}  // namespace

const std::vector<MaterialType>& materialTypes() {
  // One line per material type.
  static const std::vector<MaterialType> types{
      {"membrane", "membrane", {"young", "poisson", "thickness", "density", "wrinkling"}, readMembrane},
      {"cable", "cable", {"young", "area", "density"}, readCable},
      {"point_mass", "point_mass", {"mass"}, readPointMass},
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
