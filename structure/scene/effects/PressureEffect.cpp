// pressure: a follower pressure p(t) on a set of triangles (one entry or a list of them).
#include "structure/effects/ExternalLoads.hpp"
#include "structure/scene/ReadTimeFunction.hpp"
#include "structure/scene/effects/EffectKinds.hpp"

namespace fsi::structure {

namespace {

const std::vector<std::string> kKeys{"triangles", "value", "function"};

void build(const YamlMap& p, EffectContext& ctx) {
  const auto tris = ctx.sets.triangles(p.required("triangles"), p.childPath("triangles"));
  const double value = p.number("value");
  const TimeFunction fn = readTimeFunction(p, "function");
  p.finish(kKeys);
  std::vector<int> conn;
  for (int e : tris)
    for (int k = 0; k < 3; ++k) conn.push_back(ctx.model.membranes.conn[3 * e + k]);
  const std::string label = p.node()["triangles"].IsScalar() ? p.node()["triangles"].Scalar() : p.path();
  ctx.loads.push_back(std::make_unique<FollowerPressure>(label, std::move(conn), value, fn));
}

}  // namespace

EffectKind pressureEffect() {
  return {"pressure", kKeys, "follower pressure value*f(t) on triangles (along their current normal)",
          true,       "",    build};
}

}  // namespace fsi::structure
