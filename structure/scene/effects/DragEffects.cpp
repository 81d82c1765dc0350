// line_drag and body_drag: aerodynamic drag of lines (cross-flow principle) and of bodies (a drag area) in a
// uniform wind U·f(t), relative to the structure's velocity (structure/effects/AerodynamicDrag.hpp).
#include <fmt/format.h>

#include "structure/effects/AerodynamicDrag.hpp"
#include "structure/scene/ReadTimeFunction.hpp"
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/effects/EffectKinds.hpp"

namespace fsi::structure {

namespace {

std::vector<SceneKey> airKeys() {
  return {{"wind", KeyType::Vec3, "m/s", "", "required", {}, {}, {}, "the uniform wind U"},
          {"density",
           KeyType::Number,
           "kg/m³",
           "1.225",
           "",
           KeyBound{0, false},
           {},
           {},
           "the air's density ρ (sea level: 1.225)"},
          {"function",
           KeyType::Any,
           "",
           "",
           "constant 1",
           {},
           {},
           {},
           "scales the wind: U f(t) (docs/SCENES.md, Time functions)"}};
}

const SchemaSection& lineSchema() {
  static const SchemaSection s = [] {
    SchemaSection l{
        "effects.line_drag",
        "drag ½ρ C_D d |U_n| U_n per length of lines in a uniform wind (an entry or a list of them)",
        {{"lines", KeyType::Selector, "", "", "required", {}, {}, {}, "the cables"},
         {"diameter",
          KeyType::Number,
          "m",
          "",
          "required",
          KeyBound{0, false},
          {},
          {},
          "the lines' diameter d"},
         {"cd",
          KeyType::Number,
          "-",
          "1.0",
          "",
          KeyBound{0, true},
          {},
          {},
          "drag coefficient C_D (a cylinder in cross-flow: about 1)"}}};
    for (const SceneKey& k : airKeys()) l.keys.push_back(k);
    return l;
  }();
  return s;
}

const SchemaSection& bodySchema() {
  static const SchemaSection s = [] {
    SchemaSection b{"effects.body_drag",
                    "drag ½ρ C_D A |U−v| (U−v) of a body (payload) at nodes (an entry or a list of them)",
                    {{"nodes", KeyType::Selector, "", "", "required", {}, {}, {}, "the nodes"},
                     {"drag_area",
                      KeyType::Number,
                      "m²",
                      "",
                      "required",
                      KeyBound{0, true},
                      {},
                      {},
                      "C_D times the area, at each node"}}};
    for (const SceneKey& k : airKeys()) b.keys.push_back(k);
    return b;
  }();
  return s;
}

AirStream readAir(const SchemaMap& e) {
  AirStream a;
  a.wind = e.vec3("wind");
  a.density = e.number("density");
  a.function = readTimeFunction(e.map(), "function");
  return a;
}

std::string labelOf(const YamlMap& e, const std::string& key) {
  return e.node()[key].IsScalar() ? e.node()[key].Scalar() : e.path();
}

void buildLine(const YamlMap& e, EffectContext& ctx) {
  const SchemaMap m(e, lineSchema());
  const auto lines = ctx.sets.lines(e.required("lines"), e.childPath("lines"));
  const double d = m.number("diameter");
  const double cd = m.number("cd");
  const AirStream air = readAir(m);
  m.finish();
  std::vector<int> conn;
  for (int c : lines)
    for (int k = 0; k < 2; ++k) conn.push_back(ctx.model.cables.conn[2 * c + k]);
  ctx.loads.push_back(std::make_unique<LineDrag>(labelOf(e, "lines"), std::move(conn), d, cd, air));
}

void buildBody(const YamlMap& e, EffectContext& ctx) {
  const SchemaMap m(e, bodySchema());
  const auto nodes = ctx.sets.nodes(e.required("nodes"), e.childPath("nodes"));
  const double area = m.number("drag_area");
  const AirStream air = readAir(m);
  m.finish();
  ctx.loads.push_back(std::make_unique<BodyDrag>(labelOf(e, "nodes"), nodes, area, air));
}

}  // namespace

EffectKind lineDragEffect() {
  return {"line_drag",
          lineSchema().names(),
          "drag ½ρ C_D d |U_n| U_n per length of lines in a uniform wind",
          true,
          "",
          buildLine,
          &lineSchema()};
}

EffectKind bodyDragEffect() {
  return {
      "body_drag", bodySchema().names(), "drag ½ρ C_D A |U−v| (U−v) of a body (payload) at nodes", true, "",
      buildBody,   &bodySchema()};
}

}  // namespace fsi::structure
