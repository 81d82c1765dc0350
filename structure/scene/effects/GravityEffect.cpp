// gravity: body force m g(t) on every node, with the physical (unscaled) lumped mass.
#include "structure/effects/ExternalLoads.hpp"
#include "structure/scene/ReadTimeFunction.hpp"
#include "structure/scene/effects/EffectKinds.hpp"

namespace fsi::structure {

namespace {

const std::vector<std::string> kKeys{"acceleration", "function"};

void build(const YamlMap& g, EffectContext& ctx) {
  const auto acc = g.vec3("acceleration");
  const TimeFunction fn = readTimeFunction(g, "function");
  g.finish(kKeys);
  ctx.loads.push_back(std::make_unique<Gravity>(ctx.model.nodes.physicalMass, acc, fn));
}

}  // namespace

EffectKind gravityEffect() {
  return {"gravity", kKeys, "body force m g(t) with the physical lumped mass", false, "", build};
}

}  // namespace fsi::structure
