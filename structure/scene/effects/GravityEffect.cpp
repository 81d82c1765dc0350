// gravity: body force m g(t) on every node, with the physical (unscaled) lumped mass.
#include "structure/effects/ExternalLoads.hpp"
#include "structure/scene/ReadTimeFunction.hpp"
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/effects/EffectKinds.hpp"

namespace fsi::structure {

namespace {

const SchemaSection& schema() {
  static const SchemaSection s{
      "effects.gravity",
      "body force m g(t) with the physical lumped mass",
      {{"acceleration", KeyType::Vec3, "m/s²", "", "required", {}, {}, {}, "the acceleration of gravity g"},
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

void build(const YamlMap& entry, EffectContext& ctx) {
  const SchemaMap g(entry, schema());
  const auto acc = g.vec3("acceleration");
  const TimeFunction fn = readTimeFunction(entry, "function");
  g.finish();
  ctx.loads.push_back(std::make_unique<Gravity>(ctx.model.nodes.physicalMass, acc, fn));
}

}  // namespace

EffectKind gravityEffect() {
  return {"gravity", schema().names(), schema().description, false, "", build, &schema()};
}

}  // namespace fsi::structure
