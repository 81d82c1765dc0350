// The damping effects: mass-proportional (in the integrator), stiffness-proportional and bulk viscosity (in
// the element force kernels).
#include "structure/scene/effects/EffectKinds.hpp"

namespace fsi::structure {

namespace {

const std::vector<std::string> kMassKeys{"alpha"};
void buildMassDamping(const YamlMap& d, EffectContext& ctx) {
  ctx.integrator.massDamping = d.number("alpha");
  d.finish(kMassKeys);
  if (!(ctx.integrator.massDamping >= 0)) d.failAt("alpha", "must be >= 0");
}

const std::vector<std::string> kStiffnessKeys{"beta"};
void buildStiffnessDamping(const YamlMap& d, EffectContext& ctx) {
  ctx.elementDamping.beta = d.number("beta");
  d.finish(kStiffnessKeys);
  if (!(ctx.elementDamping.beta >= 0)) d.failAt("beta", "must be >= 0");
}

const std::vector<std::string> kBulkKeys{"b1"};
void buildBulkViscosity(const YamlMap& d, EffectContext& ctx) {
  ctx.elementDamping.bulkB1 = d.number("b1", 0.06);
  d.finish(kBulkKeys);
  if (!(ctx.elementDamping.bulkB1 >= 0)) d.failAt("b1", "must be >= 0");
}

}  // namespace

EffectKind massDampingEffect() {
  return {"mass_damping",
          kMassKeys,
          "mass-proportional damping force -alpha m v",
          false,
          "dynamic relaxation brings its own damping (solver.damping); remove this effect",
          buildMassDamping};
}

EffectKind stiffnessDampingEffect() {
  return {"stiffness_damping",
          kStiffnessKeys,
          "stiffness-proportional (Rayleigh) damping beta C:dE/dt",
          false,
          "",
          buildStiffnessDamping};
}

EffectKind bulkViscosityEffect() {
  return {"bulk_viscosity",  kBulkKeys, "linear bulk viscosity b1 rho c L tr(dE/dt)", false, "",
          buildBulkViscosity};
}

}  // namespace fsi::structure
