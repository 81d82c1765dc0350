// canopy_pressure: the semi-empirical load on a round canopy in a relative wind (structure/effects/
// CanopyPressure): inside, the air that has entered the mouth (Bernoulli and continuity: the stagnation
// pressure once the canopy holds its air, less while it grows faster than air comes in or leaks out through
// porous cloth and the vent); outside, the impact law where the wind meets the cloth and a wake suction
// elsewhere; for inflation and descent runs without a flow solver (docs/ROUND_CANOPY.md).
#include <cmath>

#include "structure/effects/CanopyPressure.hpp"
#include "structure/scene/ReadTimeFunction.hpp"
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/effects/EffectKinds.hpp"

namespace fsi::structure {

namespace {

const SchemaSection& schema() {
  using T = KeyType;
  static const SchemaSection s{
      "effects.canopy_pressure",
      "a round canopy in a relative wind: the air inside (stagnation pressure, less while the canopy fills "
      "or leaks), the impact law and a wake suction outside (an entry or a list of them)",
      {{"triangles", T::Selector, "", "", "required", {}, {}, {}, "the canopy's cloth (normals outwards)"},
       {"mouth", T::Selector, "", "", "required", {}, {}, {}, "the nodes around the mouth (the skirt)"},
       {"vent", T::Selector, "", "", "none", {}, {}, {}, "the nodes around the vent (none: closed)"},
       {"wind",
        T::Vec3,
        "m/s",
        "",
        "required",
        {},
        {},
        {},
        "the uniform wind U (relative wind: U f(t) − the canopy's mean velocity)"},
       {"density", T::Number, "kg/m³", "1.225", "", excl(0), {}, {}, "the air's density ρ"},
       {"function", T::Any, "", "", "constant 1", {}, {}, {}, "scales the wind: U f(t) (Time functions)"},
       {"cp_max", T::Number, "-", "1.0", "", excl(0), incl(2), {}, "C_p,max of the impact law outside"},
       {"exponent", T::Number, "-", "2", "", excl(0), incl(4), {}, "n of cosⁿ (2: the Newtonian impact law)"},
       {"wake_cp",
        T::Number,
        "-",
        "0",
        "",
        incl(0),
        incl(2),
        {},
        "suction on the leeward outer face, in ½ρW²"},
       {"vent_discharge",
        T::Number,
        "-",
        "0.6",
        "",
        excl(0),
        incl(1),
        {},
        "the vent's discharge coefficient"},
       {"suction_limit",
        T::Number,
        "-",
        "1.0",
        "",
        incl(0),
        incl(10),
        {},
        "the inside pressure is at least −suction_limit ½ρW²"},
       {"darcy",
        T::Number,
        "1/m",
        "0",
        "",
        incl(0),
        {},
        {},
        "the cloth's viscous coefficient a (0 with forchheimer 0: impermeable)"},
       {"forchheimer", T::Number, "-", "0", "", incl(0), {}, {}, "the cloth's inertial coefficient b"},
       {"apparent_mass",
        T::Number,
        "m",
        "0",
        "",
        incl(0),
        {},
        {},
        "inertia of the air moved with the cloth: a layer this thick (ρ h per cloth area, lumped to the "
        "cloth's nodes; no weight)"},
       {"viscosity", T::Number, "Pa s", "1.8e-5", "", excl(0), {}, {}, "the air's dynamic viscosity μ"}}};
  return s;
}

// The air moved with the cloth: ρ h per reference cloth area, a third of each triangle's to its nodes, as
// inertia only (mass, not physicalMass: the air has no weight in air). The constraints zero the held dofs'
// inverse masses when the run starts.
void addApparentMass(Model& model, const std::vector<int>& conn, double perArea) {
  Nodes& N = model.nodes;
  for (std::size_t e = 0; 3 * e < conn.size(); ++e) {
    const int a = conn[3 * e], b = conn[3 * e + 1], c = conn[3 * e + 2];
    double d21[3], d31[3];
    for (int k = 0; k < 3; ++k) {
      d21[k] = N.X[3 * b + k] - N.X[3 * a + k];
      d31[k] = N.X[3 * c + k] - N.X[3 * a + k];
    }
    const double area = 0.5 * std::sqrt(std::pow(d21[1] * d31[2] - d21[2] * d31[1], 2) +
                                        std::pow(d21[2] * d31[0] - d21[0] * d31[2], 2) +
                                        std::pow(d21[0] * d31[1] - d21[1] * d31[0], 2));
    for (int n : {a, b, c}) N.mass[n] += perArea * area / 3.0;
  }
  for (int i = 0; i < N.count; ++i)
    for (int k = 0; k < 3; ++k) N.invMassDof[3 * i + k] = 1.0 / N.mass[i];
}

void build(const YamlMap& e, EffectContext& ctx) {
  const SchemaMap m(e, schema());
  const auto tris = ctx.sets.triangles(e.required("triangles"), e.childPath("triangles"));
  const auto mouth = ctx.sets.nodes(e.required("mouth"), e.childPath("mouth"));
  std::vector<int> vent;
  if (e.has("vent")) vent = ctx.sets.nodes(e.required("vent"), e.childPath("vent"));
  AirStream air;
  air.wind = m.vec3("wind");
  air.density = m.number("density");
  air.function = readTimeFunction(e, "function");
  CanopyPressureParams prm;
  prm.cpMax = m.number("cp_max");
  prm.exponent = m.number("exponent");
  prm.wakeCp = m.number("wake_cp");
  prm.ventDischarge = m.number("vent_discharge");
  prm.suctionLimit = m.number("suction_limit");
  prm.cloth.a = m.number("darcy");
  prm.cloth.b = m.number("forchheimer");
  prm.cloth.viscosity = m.number("viscosity");
  const double layer = m.number("apparent_mass");
  m.finish();
  if (mouth.size() < 3) e.failAt("mouth", "needs at least 3 nodes around the mouth");
  if (!vent.empty() && vent.size() < 3) e.failAt("vent", "needs at least 3 nodes around the vent");
  std::vector<int> conn;
  for (int t : tris)
    for (int k = 0; k < 3; ++k) conn.push_back(ctx.model.membranes.conn[3 * t + k]);
  if (layer > 0) addApparentMass(ctx.model, conn, air.density * layer);
  const std::string label = e.node()["triangles"].IsScalar() ? e.node()["triangles"].Scalar() : e.path();
  ctx.loads.push_back(std::make_unique<CanopyPressureLoad>(
      label, std::move(conn), std::vector<int>(mouth.begin(), mouth.end()),
      std::vector<int>(vent.begin(), vent.end()), std::move(air), prm));
}

}  // namespace

EffectKind canopyPressureEffect() {
  return {"canopy_pressure", schema().names(), schema().description, true, "", build, &schema()};
}

}  // namespace fsi::structure
