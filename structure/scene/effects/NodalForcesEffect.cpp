// nodal_forces: the same force f(t) F on every node of a set (one entry or a list of them).
#include "structure/effects/ExternalLoads.hpp"
#include "structure/scene/ReadTimeFunction.hpp"
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/effects/EffectKinds.hpp"

namespace fsi::structure {

namespace {

const SchemaSection& schema() {
  static const SchemaSection s{
      "effects.nodal_forces",
      "force f(t) F on every node of a set (an entry or a list of them)",
      {{"nodes", KeyType::Selector, "", "", "required", {}, {}, {}, "the nodes"},
       {"force", KeyType::Vec3, "N", "", "required", {}, {}, {}, "the force F on each node (not shared)"},
       {"function",
        KeyType::Any,
        "",
        "",
        "constant 1",
        {},
        {},
        {},
        "a time function f(t) (docs/SCENES.md, Time functions)"}}};
  return s;
}

void build(const YamlMap& p, EffectContext& ctx) {
  const SchemaMap m(p, schema());
  const auto nodes = ctx.sets.nodes(p.required("nodes"), p.childPath("nodes"));
  const auto f = m.vec3("force");
  const TimeFunction fn = readTimeFunction(p, "function");
  m.finish();
  ctx.loads.push_back(std::make_unique<NodalForces>(p.path(), nodes, f, fn));
}

}  // namespace

EffectKind nodalForcesEffect() {
  return {"nodal_forces", schema().names(), "force f(t) F on every node of a set", true, "",
          build,          &schema()};
}

}  // namespace fsi::structure
