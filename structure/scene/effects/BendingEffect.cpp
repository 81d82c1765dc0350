// bending: the flexural rigidity D of a fabric as hinges on the interior edges of a triangle set
// (structure/effects/FabricBending.hpp).
#include <fmt/format.h>

#include "structure/effects/FabricBending.hpp"
#include "structure/scene/effects/EffectKinds.hpp"

namespace fsi::structure {

namespace {

const std::vector<std::string> kKeys{"triangles", "rigidity"};

void build(const YamlMap& b, EffectContext& ctx) {
  const auto tris = ctx.sets.triangles(b.required("triangles"), b.childPath("triangles"));
  const double D = b.number("rigidity");
  if (!isPositiveNormal(D))
    b.failAt("rigidity",
             fmt::format(
                 "is {}; valid: > 0, at least 2.2e-308 [N·m] (a woven parachute fabric: about 1e-6 to 1e-4; "
                 "an isotropic sheet: E t³ / 12(1 − ν²))",
                 D));
  b.finish(kKeys);
  std::vector<int> conn;
  for (int e : tris)
    for (int k = 0; k < 3; ++k) conn.push_back(ctx.model.membranes.conn[3 * e + k]);
  const std::string label = b.node()["triangles"].IsScalar() ? b.node()["triangles"].Scalar() : b.path();
  auto effect = std::make_unique<FabricBending>(label, conn, ctx.model.nodes.X, &ctx.model.nodes.mass, D);
  if (effect->hinges() == 0)
    b.failAt("triangles",
             fmt::format("'{}': no two of its triangles share an edge, so nothing can bend", label));
  ctx.loads.push_back(std::move(effect));
}

}  // namespace

EffectKind bendingEffect() {
  return {"bending",
          kKeys,
          "flexural rigidity D of a fabric: hinges ½ k (θ − θ0)² on the interior edges of triangles",
          true,
          "",
          build};
}

}  // namespace fsi::structure
