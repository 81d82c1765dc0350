#include "structure/model/MaterialKeys.hpp"

#include <fmt/format.h>

#include "structure/model/Error.hpp"

namespace fsi::structure {

namespace {

constexpr KeyBound kAboveZero{0, false};

SceneKey typeKey(const char* type) {
  return {"type", KeyType::Choice, "", "", "required", {}, {}, {type}, "the material type"};
}

void check(const SchemaSection& s, const std::string& material, const std::string& key, double v) {
  const SceneKey& k = s.key(key);
  if (!k.inRange(v))
    throw InputError(
        fmt::format("material '{}': {} {}", material, key, k.rangeMessage(fmt::format("{:g}", v))));
}

}  // namespace

const SchemaSection& membraneMaterialKeys() {
  static const SchemaSection s{
      "materials.NAME (type: membrane)",
      "an isotropic membrane (St Venant-Kirchhoff in Green-Lagrange strain), tension field if wrinkling",
      {typeKey("membrane"),
       {"young", KeyType::Number, "Pa", "", "required", kAboveZero, {}, {}, "Young's modulus E"},
       {"poisson",
        KeyType::Number,
        "-",
        "",
        "required",
        KeyBound{0, true},
        KeyBound{0.5, false},
        {},
        "Poisson's ratio ν"},
       {"thickness", KeyType::Number, "m", "", "required", kAboveZero, {}, {}, "reference thickness t"},
       {"density", KeyType::Number, "kg/m³", "", "required", kAboveZero, {}, {}, "mass density ρ"},
       {"wrinkling",
        KeyType::Boolean,
        "",
        "true",
        "",
        {},
        {},
        {},
        "true: a tension-field membrane that carries no compression; false: plain plane stress"}}};
  return s;
}

const SchemaSection& cableMaterialKeys() {
  static const SchemaSection s{
      "materials.NAME (type: cable)",
      "a tension-only cable",
      {typeKey("cable"),
       {"young", KeyType::Number, "Pa", "", "required", kAboveZero, {}, {}, "Young's modulus E"},
       {"area", KeyType::Number, "m²", "", "required", kAboveZero, {}, {}, "cross-section A"},
       {"density", KeyType::Number, "kg/m³", "", "required", kAboveZero, {}, {}, "mass density ρ"}}};
  return s;
}

const SchemaSection& pointMassMaterialKeys() {
  static const SchemaSection s{"materials.NAME (type: point_mass)",
                               "a lumped mass on every node of a mesh's node group (`point_masses:`)",
                               {typeKey("point_mass"),
                                {"mass",
                                 KeyType::Number,
                                 "kg",
                                 "",
                                 "required",
                                 kAboveZero,
                                 {},
                                 {},
                                 "mass on each node that carries it"}}};
  return s;
}

void checkMaterial(const MembraneMaterial& m) {
  const SchemaSection& s = membraneMaterialKeys();
  check(s, m.name, "young", m.young);
  check(s, m.name, "poisson", m.poisson);
  check(s, m.name, "thickness", m.thickness);
  check(s, m.name, "density", m.density);
}

void checkMaterial(const CableMaterial& m) {
  const SchemaSection& s = cableMaterialKeys();
  check(s, m.name, "young", m.young);
  check(s, m.name, "area", m.area);
  check(s, m.name, "density", m.density);
}

void checkMaterial(const PointMassMaterial& m) {
  check(pointMassMaterialKeys(), m.name, "mass", m.mass);
}

}  // namespace fsi::structure
