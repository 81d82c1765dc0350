// pressure: a follower pressure p(t) on a set of triangles (one entry or a list of them).
#include "structure/effects/ExternalLoads.hpp"
#include "structure/scene/ReadTimeFunction.hpp"
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/effects/EffectKinds.hpp"

namespace fsi::structure {

namespace {

const SchemaSection& schema() {
  static const SchemaSection s{
      "effects.pressure",
      "follower pressure value*f(t) on triangles (along their current normal; an entry or a list of them)",
      {{"triangles", KeyType::Selector, "", "", "required", {}, {}, {}, "the triangles"},
       {"value",
        KeyType::Number,
        "Pa",
        "",
        "required",
        {},
        {},
        {},
        "the pressure p (positive: along the normal)"},
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
  const auto tris = ctx.sets.triangles(p.required("triangles"), p.childPath("triangles"));
  const double value = m.number("value");
  const TimeFunction fn = readTimeFunction(p, "function");
  m.finish();
  std::vector<int> conn;
  for (int e : tris)
    for (int k = 0; k < 3; ++k) conn.push_back(ctx.model.membranes.conn[3 * e + k]);
  const std::string label = p.node()["triangles"].IsScalar() ? p.node()["triangles"].Scalar() : p.path();
  ctx.loads.push_back(std::make_unique<FollowerPressure>(label, std::move(conn), value, fn));
}

}  // namespace

EffectKind pressureEffect() {
  return {"pressure",
          schema().names(),
          "follower pressure value*f(t) on triangles (along their current normal)",
          true,
          "",
          build,
          &schema()};
}

}  // namespace fsi::structure
