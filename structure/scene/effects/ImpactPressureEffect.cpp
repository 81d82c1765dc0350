// impact_pressure: the semi-empirical pressure on cloth in a relative wind
// (structure/effects/ImpactPressure): the impact law C_p,max ½ρ|w|² cosⁿ on each triangle facing the wind,
// reduced by the cloth's porosity (Darcy–Forchheimer a, b); for inflation and descent runs without a flow
// solver (docs/ROUND_CANOPY.md).
#include "structure/effects/ImpactPressure.hpp"
#include "structure/scene/ReadTimeFunction.hpp"
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/effects/EffectKinds.hpp"

namespace fsi::structure {

namespace {

const SchemaSection& schema() {
  using T = KeyType;
  static const SchemaSection s{
      "effects.impact_pressure",
      "cloth in a relative wind: C_p,max ½ρ|w|² cosⁿ on triangles facing it, less what porous cloth lets "
      "through (an entry or a list of them)",
      {{"triangles", T::Selector, "", "", "required", {}, {}, {}, "the cloth"},
       {"wind",
        T::Vec3,
        "m/s",
        "",
        "required",
        {},
        {},
        {},
        "the uniform wind U (w = U f(t) − the cloth's velocity)"},
       {"density", T::Number, "kg/m³", "1.225", "", excl(0), {}, {}, "the air's density ρ"},
       {"function", T::Any, "", "", "constant 1", {}, {}, {}, "scales the wind: U f(t) (Time functions)"},
       {"cp_max", T::Number, "-", "1.0", "", excl(0), incl(2), {}, "C_p,max, the stagnation value"},
       {"exponent", T::Number, "-", "2", "", excl(0), incl(4), {}, "n of cosⁿ (2: the Newtonian impact law)"},
       {"darcy",
        T::Number,
        "1/m",
        "0",
        "",
        incl(0),
        {},
        {},
        "the cloth's viscous coefficient a (0 with "
        "forchheimer 0: impermeable)"},
       {"forchheimer", T::Number, "-", "0", "", incl(0), {}, {}, "the cloth's inertial coefficient b"},
       {"viscosity", T::Number, "Pa s", "1.8e-5", "", excl(0), {}, {}, "the air's dynamic viscosity μ"}}};
  return s;
}

void build(const YamlMap& e, EffectContext& ctx) {
  const SchemaMap m(e, schema());
  const auto tris = ctx.sets.triangles(e.required("triangles"), e.childPath("triangles"));
  AirStream air;
  air.wind = m.vec3("wind");
  air.density = m.number("density");
  air.function = readTimeFunction(e, "function");
  const double cpMax = m.number("cp_max"), exponent = m.number("exponent");
  ClothPermeability cloth;
  cloth.a = m.number("darcy");
  cloth.b = m.number("forchheimer");
  cloth.viscosity = m.number("viscosity");
  m.finish();
  std::vector<int> conn;
  for (int t : tris)
    for (int k = 0; k < 3; ++k) conn.push_back(ctx.model.membranes.conn[3 * t + k]);
  const std::string label = e.node()["triangles"].IsScalar() ? e.node()["triangles"].Scalar() : e.path();
  ctx.loads.push_back(
      std::make_unique<ImpactPressureLoad>(label, std::move(conn), std::move(air), cpMax, exponent, cloth));
}

}  // namespace

EffectKind impactPressureEffect() {
  return {"impact_pressure", schema().names(), schema().description, true, "", build, &schema()};
}

}  // namespace fsi::structure
