// The damping effects: mass-proportional (in the integrator), stiffness-proportional and bulk viscosity (in
// the element force kernels).
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/effects/EffectKinds.hpp"

namespace fsi::structure {

namespace {

const SchemaSection& massSchema() {
  static const SchemaSection s{"effects.mass_damping",
                               "mass-proportional damping force -alpha m v",
                               {{"alpha",
                                 KeyType::Number,
                                 "1/s",
                                 "",
                                 "required",
                                 KeyBound{0, true},
                                 {},
                                 {},
                                 "the damping coefficient α"}}};
  return s;
}

void buildMassDamping(const YamlMap& entry, EffectContext& ctx) {
  const SchemaMap d(entry, massSchema());
  ctx.integrator.massDamping = d.number("alpha");
  d.finish();
}

const SchemaSection& stiffnessSchema() {
  static const SchemaSection s{"effects.stiffness_damping",
                               "stiffness-proportional (Rayleigh) damping beta C:dE/dt",
                               {{"beta",
                                 KeyType::Number,
                                 "s",
                                 "",
                                 "required",
                                 KeyBound{0, true},
                                 {},
                                 {},
                                 "the damping coefficient β (lowers the stable step)"}}};
  return s;
}

void buildStiffnessDamping(const YamlMap& entry, EffectContext& ctx) {
  const SchemaMap d(entry, stiffnessSchema());
  ctx.elementDamping.beta = d.number("beta");
  d.finish();
}

const SchemaSection& bulkSchema() {
  static const SchemaSection s{"effects.bulk_viscosity",
                               "linear bulk viscosity b1 rho c L tr(dE/dt)",
                               {{"b1",
                                 KeyType::Number,
                                 "-",
                                 "0.06",
                                 "",
                                 KeyBound{0, true},
                                 {},
                                 {},
                                 "the damping ratio of an element's highest mode"}}};
  return s;
}

void buildBulkViscosity(const YamlMap& entry, EffectContext& ctx) {
  const SchemaMap d(entry, bulkSchema());
  ctx.elementDamping.bulkB1 = d.number("b1");
  d.finish();
}

}  // namespace

EffectKind massDampingEffect() {
  return {"mass_damping",
          massSchema().names(),
          massSchema().description,
          false,
          "dynamic relaxation brings its own damping (solver.damping); remove this effect",
          buildMassDamping,
          &massSchema()};
}

EffectKind stiffnessDampingEffect() {
  return {"stiffness_damping",   stiffnessSchema().names(), stiffnessSchema().description, false, "",
          buildStiffnessDamping, &stiffnessSchema()};
}

EffectKind bulkViscosityEffect() {
  return {"bulk_viscosity",   bulkSchema().names(), bulkSchema().description, false, "",
          buildBulkViscosity, &bulkSchema()};
}

}  // namespace fsi::structure
