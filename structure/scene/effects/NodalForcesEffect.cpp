// nodal_forces: the same force f(t) F on every node of a set (one entry or a list of them).
#include "structure/effects/ExternalLoads.hpp"
#include "structure/scene/ReadTimeFunction.hpp"
#include "structure/scene/effects/EffectKinds.hpp"

namespace fsi::structure {

namespace {

const std::vector<std::string> kKeys{"nodes", "force", "function"};

void build(const YamlMap& p, EffectContext& ctx) {
  const auto nodes = ctx.sets.nodes(p.required("nodes"), p.childPath("nodes"));
  const auto f = p.vec3("force");
  const TimeFunction fn = readTimeFunction(p, "function");
  p.finish(kKeys);
  ctx.loads.push_back(std::make_unique<NodalForces>(p.path(), nodes, f, fn));
}

}  // namespace

EffectKind nodalForcesEffect() {
  return {"nodal_forces", kKeys, "force f(t) F on every node of a set", true, "", build};
}

}  // namespace fsi::structure
