// chordwise_pressure: the pressure of an outer flow, q·Cp(x/c) from a pressure-coefficient table along a
// chord, on a set of triangles (one-way FSI from a panel code, a wind tunnel or CFD). The flow is on the side
// the triangles' normals point to (an outward skin): a positive Cp pushes against the normal, into the
// canopy; suction (Cp < 0) pulls outward. Each triangle takes the value at its reference centroid.
#include <fmt/format.h>

#include "structure/effects/PressureDistribution.hpp"
#include "structure/model/Error.hpp"
#include "structure/scene/ReadTimeFunction.hpp"
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/effects/EffectKinds.hpp"

namespace fsi::structure {

namespace {

// The entry's keys; read by build() with its own messages (the cp table's rows, a zero axis).
const SchemaSection& schema() {
  using T = KeyType;
  static const SchemaSection s{
      "effects.chordwise_pressure",
      "outer-flow pressure q*Cp(x/c) from a chordwise table on triangles (flow on the normal side; an entry "
      "or "
      "a list of them)",
      {{"triangles",
        T::Selector,
        "",
        "",
        "required",
        {},
        {},
        {},
        "the triangles (each takes Cp at its centroid)"},
       {"dynamic_pressure", T::Number, "Pa", "", "required", {}, {}, {}, "q"},
       {"cp",
        T::Any,
        "",
        "",
        "required",
        {},
        {},
        {},
        "the table [[x/c, Cp], ...], x/c increasing (Cp > 0 pushes against the normal)"},
       {"leading_edge", T::Vec3, "m", "[0, 0, 0]", "", {}, {}, {}, "where x/c = 0"},
       {"axis",
        T::Vec3,
        "-",
        "[1, 0, 0]",
        "",
        {},
        {},
        {},
        "the chord direction (non-zero, need not be unit)"},
       {"chord",
        T::Number,
        "m",
        "",
        "required",
        excl(0),
        {},
        {},
        "c: x/c = (x - leading_edge)·axis/|axis|/c"},
       {"function",
        T::Any,
        "",
        "",
        "constant 1",
        {},
        {},
        {},
        "a time function f(t) (docs/SCENES.md, Time functions)"},
       {"follower",
        T::Boolean,
        "",
        "true",
        "",
        {},
        {},
        {},
        "follow the current area and normal (false: a dead load on the reference geometry)"}}};
  return s;
}

void build(const YamlMap& e, EffectContext& ctx) {
  const auto tris = ctx.sets.triangles(e.required("triangles"), e.childPath("triangles"));
  const double q = e.number("dynamic_pressure");
  CpTable table;
  const YAML::Node rows = e.required("cp");
  if (!rows.IsSequence() || rows.size() < 1)
    e.failAt("cp", "expected a list of [x/c, Cp] pairs, x/c increasing");
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::string p = fmt::format("{}[{}]", e.childPath("cp"), i);
    if (!rows[i].IsSequence() || rows[i].size() != 2)
      throw InputError(locate(e.file(), rows[i], p) + ": expected [x/c, Cp]");
    const double x = asNumber(rows[i][0], e.file(), p), c = asNumber(rows[i][1], e.file(), p);
    if (!table.xc.empty() && !(x > table.xc.back()))
      throw InputError(locate(e.file(), rows[i], p) +
                       fmt::format(": x/c = {} must be larger than the row before ({})", x, table.xc.back()));
    table.xc.push_back(x);
    table.cp.push_back(c);
  }
  const auto le = e.vec3("leading_edge", {0, 0, 0});
  const auto axis = e.vec3("axis", {1, 0, 0});
  if (!(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2] > 0)) e.failAt("axis", "must not be zero");
  const double chord = e.number("chord");
  if (!isPositiveNormal(chord)) e.failAt("chord", fmt::format("is {}; {} [m]", chord, kPositiveRule));
  const TimeFunction fn = readTimeFunction(e, "function");
  const bool follower = e.boolean("follower", true);
  e.finish(schema().names());
  std::vector<int> conn;
  for (int t : tris)
    for (int k = 0; k < 3; ++k) conn.push_back(ctx.model.membranes.conn[3 * t + k]);
  // −q·Cp along the normal: the flow's pressure acts from the side the normal points to.
  auto values = chordwisePressure(ctx.model.nodes.X, conn, table, -q, le, axis, chord);
  addTrianglePressure(e, ctx, std::move(conn), std::move(values), fn, follower);
}

}  // namespace

void addTrianglePressure(const YamlMap& e, EffectContext& ctx, std::vector<int> conn,
                         std::vector<double> values, const TimeFunction& fn, bool follower) {
  const std::string label = e.node()["triangles"].IsScalar() ? e.node()["triangles"].Scalar() : e.path();
  if (follower)
    ctx.loads.push_back(
        std::make_unique<PressureDistribution>(label, std::move(conn), std::move(values), fn));
  else
    ctx.loads.push_back(std::make_unique<PressureDistribution>(
        PressureDistribution::dead(label, std::move(conn), std::move(values), fn, ctx.model.nodes.X)));
}

EffectKind chordwisePressureEffect() {
  return {"chordwise_pressure",
          schema().names(),
          "outer-flow pressure q·Cp(x/c) from a chordwise table on triangles (flow on the normal side)",
          true,
          "",
          build,
          &schema()};
}

}  // namespace fsi::structure
