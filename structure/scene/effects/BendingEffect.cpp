// bending: the flexural rigidity D of a fabric as hinges on the interior edges of a triangle set
// (structure/effects/FabricBending.hpp).
#include <fmt/format.h>

#include "structure/effects/FabricBending.hpp"
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/effects/EffectKinds.hpp"

namespace fsi::structure {

namespace {

const SchemaSection& schema() {
  static const SchemaSection s{
      "effects.bending",
      "flexural rigidity D of a fabric: hinges on the interior edges of triangles (an entry or a list of "
      "them)",
      {{"triangles", KeyType::Selector, "", "", "required", {}, {}, {}, "the triangles"},
       {"rigidity",
        KeyType::Number,
        "N·m",
        "",
        "required",
        KeyBound{0, false},
        {},
        {},
        "D: a woven parachute fabric about 1e-6 to 1e-4; an isotropic sheet E t³ / 12(1 − ν²)"}}};
  return s;
}

void build(const YamlMap& b, EffectContext& ctx) {
  const SchemaMap m(b, schema());
  const auto tris = ctx.sets.triangles(b.required("triangles"), b.childPath("triangles"));
  const double D = m.number("rigidity");
  m.finish();
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
          schema().names(),
          "flexural rigidity D of a fabric: hinges ½ k (θ − θ0)² on the interior edges of triangles",
          true,
          "",
          build,
          &schema()};
}

}  // namespace fsi::structure
