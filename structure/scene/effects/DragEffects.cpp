// line_drag and body_drag: aerodynamic drag of lines (cross-flow principle) and of bodies (a drag area) in a
// uniform wind U·f(t), relative to the structure's velocity (structure/effects/AerodynamicDrag.hpp).
#include <fmt/format.h>

#include "structure/effects/AerodynamicDrag.hpp"
#include "structure/scene/ReadTimeFunction.hpp"
#include "structure/scene/effects/EffectKinds.hpp"

namespace fsi::structure {

namespace {

const std::vector<std::string> kLineKeys{"lines", "diameter", "cd", "wind", "density", "function"};
const std::vector<std::string> kBodyKeys{"nodes", "drag_area", "wind", "density", "function"};

AirStream readAir(const YamlMap& e) {
  AirStream a;
  a.wind = e.vec3("wind");
  a.density = e.number("density", 1.225);
  if (!isPositiveNormal(a.density))
    e.failAt("density", fmt::format("is {}; {} (air at sea level: 1.225)", a.density, kPositiveRule));
  a.function = readTimeFunction(e, "function");
  return a;
}

std::string labelOf(const YamlMap& e, const std::string& key) {
  return e.node()[key].IsScalar() ? e.node()[key].Scalar() : e.path();
}

void buildLine(const YamlMap& e, EffectContext& ctx) {
  const auto lines = ctx.sets.lines(e.required("lines"), e.childPath("lines"));
  const double d = e.number("diameter");
  if (!isPositiveNormal(d)) e.failAt("diameter", fmt::format("is {}; {} [m]", d, kPositiveRule));
  const double cd = e.number("cd", 1.0);
  if (!(cd >= 0)) e.failAt("cd", fmt::format("is {}; valid: >= 0 (a cylinder in cross-flow: about 1)", cd));
  const AirStream air = readAir(e);
  e.finish(kLineKeys);
  std::vector<int> conn;
  for (int c : lines)
    for (int k = 0; k < 2; ++k) conn.push_back(ctx.model.cables.conn[2 * c + k]);
  ctx.loads.push_back(std::make_unique<LineDrag>(labelOf(e, "lines"), std::move(conn), d, cd, air));
}

void buildBody(const YamlMap& e, EffectContext& ctx) {
  const auto nodes = ctx.sets.nodes(e.required("nodes"), e.childPath("nodes"));
  const double area = e.number("drag_area");
  if (!(area >= 0)) e.failAt("drag_area", fmt::format("is {}; valid: >= 0 (C_D times the area, m²)", area));
  const AirStream air = readAir(e);
  e.finish(kBodyKeys);
  ctx.loads.push_back(std::make_unique<BodyDrag>(labelOf(e, "nodes"), nodes, area, air));
}

}  // namespace

EffectKind lineDragEffect() {
  return {"line_drag", kLineKeys, "drag ½ρ C_D d |U_n| U_n per length of lines in a uniform wind",
          true,        "",        buildLine};
}

EffectKind bodyDragEffect() {
  return {"body_drag", kBodyKeys, "drag ½ρ C_D A |U−v| (U−v) of a body (payload) at nodes",
          true,        "",        buildBody};
}

}  // namespace fsi::structure
