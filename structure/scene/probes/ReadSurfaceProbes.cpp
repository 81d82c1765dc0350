// The scene readers of the probes on triangles and lines: volume, projected_diameter, stress, line_tension,
// laplace, folds
// (what they compute: structure/probes/).
#include <fmt/format.h>

#include <cmath>

#include "structure/effects/FabricBending.hpp"
#include "structure/probes/LaplaceProbe.hpp"
#include "structure/scene/probes/ReadProbes.hpp"

namespace fsi::structure {

namespace {

void readVolume(const SchemaMap& p, const SetResolver& sets, ProbeSpec& spec) {
  spec.triangles = sets.triangles(p.map().required("triangles"), p.map().childPath("triangles"));
  spec.center = p.vec3("center");
  p.finish();
}

void readProjectedDiameter(const SchemaMap& p, const SetResolver& sets, ProbeSpec& spec) {
  spec.triangles = sets.triangles(p.map().required("triangles"), p.map().childPath("triangles"));
  spec.direction = p.vec3("direction");
  if (!(std::abs(spec.direction[0]) + std::abs(spec.direction[1]) + std::abs(spec.direction[2]) > 0))
    p.map().failAt("direction", "must not be zero");
  p.finish();
}

void readStress(const SchemaMap& p, const SetResolver& sets, ProbeSpec& spec) {
  spec.triangles = sets.triangles(p.map().required("triangles"), p.map().childPath("triangles"));
  spec.quantity =
      p.string("quantity") == "min_principal" ? StressQuantity::MinPrincipal : StressQuantity::MaxPrincipal;
  spec.reduce = readReduce(p);
  // The mean is over the surface (area-weighted, current areas): on a graded mesh an element count would
  // weight small triangles as much as large ones.
  if (spec.reduce == ProbeReduce::Mean) {
    spec.areaWeighted = true;
    spec.reduce = ProbeReduce::Sum;
  }
  p.finish();
}

void readLineTension(const SchemaMap& p, const SetResolver& sets, ProbeSpec& spec) {
  spec.lines = sets.lines(p.map().required("lines"), p.map().childPath("lines"));
  spec.reduce = readReduce(p);
  p.finish();
}

void readLaplace(const SchemaMap& p, const SetResolver& sets, ProbeSpec& spec) {
  const YamlMap& m = p.map();
  spec.nodes = sets.nodes(m.required("nodes"), m.childPath("nodes"));
  spec.triangles = sets.triangles(m.required("triangles"), m.childPath("triangles"));
  static const std::vector<std::pair<std::string, LaplaceQuantity>> names{
      {"ratio", LaplaceQuantity::Ratio},
      {"simple_ratio", LaplaceQuantity::SimpleRatio},
      {"radius", LaplaceQuantity::Radius},
      {"tension", LaplaceQuantity::Tension},
      {"pressure", LaplaceQuantity::Pressure}};
  const std::string q = p.string("quantity");
  for (const auto& [name, value] : names)
    if (name == q) spec.laplace = value;
  const bool directional =
      spec.laplace != LaplaceQuantity::Ratio && spec.laplace != LaplaceQuantity::Pressure;
  if (directional) {
    if (!p.has("direction")) m.required("direction");  // the located "missing required key"
    spec.direction = p.vec3("direction");
    const auto& d = spec.direction;
    if (!(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > 0)) m.failAt("direction", "must not be the zero vector");
  } else if (p.has("direction")) {
    m.failAt("direction",
             fmt::format("is only used by the quantities simple_ratio, radius and tension, not {}", q));
  }
  spec.reduce = readReduce(p);
  spec.rings = int(p.integer("rings"));
  p.finish();
  for (int n : spec.nodes) {
    const std::string problem = laplaceFitProblem(sets.model(), spec.triangles, n, spec.rings);
    if (!problem.empty()) m.failAt("nodes", problem);
  }
}

void readFolds(const SchemaMap& p, const SetResolver& sets, ProbeSpec& spec) {
  spec.reduce = ProbeReduce::Value;
  spec.triangles = sets.triangles(p.map().required("triangles"), p.map().childPath("triangles"));
  spec.angle = p.number("angle");
  p.finish();
  // The hinges, once, into spec.nodes (4 nodes each).
  const auto& conn = sets.model().membranes.conn;
  std::vector<int> subset;
  for (int t : spec.triangles)
    for (int k = 0; k < 3; ++k) subset.push_back(conn[3 * std::size_t(t) + std::size_t(k)]);
  spec.nodes = interiorHinges(subset).nodes;
}

}  // namespace

ProbeReader volumeReader() {
  static const SchemaSection s{
      "probes.NAME (type: volume)",
      findProbeKindDescription("volume"),
      {probeTypeKey("volume"),
       selectorKey("triangles", "the closed surface's triangles"),
       {"center", KeyType::Vec3, "m", "[0, 0, 0]", "", {}, {}, {}, "the point the volume is taken about"}}};
  return {"volume", &s, readVolume};
}

ProbeReader projectedDiameterReader() {
  static const SchemaSection s{
      "probes.NAME (type: projected_diameter)",
      findProbeKindDescription("projected_diameter"),
      {probeTypeKey("projected_diameter"),
       selectorKey("triangles", "the surface (a canopy's cloth)"),
       {"direction", KeyType::Vec3, "", "[0, 0, 1]", "", {}, {}, {}, "the axis it is seen along"}}};
  return {"projected_diameter", &s, readProjectedDiameter};
}

ProbeReader stressReader() {
  static const SchemaSection s{"probes.NAME (type: stress)",
                               findProbeKindDescription("stress"),
                               {probeTypeKey("stress"),
                                selectorKey("triangles", "the triangles"),
                                {"quantity",
                                 KeyType::Choice,
                                 "",
                                 "max_principal",
                                 "",
                                 {},
                                 {},
                                 {"max_principal", "min_principal"},
                                 "which principal stress"},
                                reduceKey({"max", "min", "mean"}, "max")}};
  return {"stress", &s, readStress};
}

ProbeReader lineTensionReader() {
  static const SchemaSection s{"probes.NAME (type: line_tension)",
                               findProbeKindDescription("line_tension"),
                               {probeTypeKey("line_tension"), selectorKey("lines", "the cables"),
                                reduceKey({"max", "min", "mean", "sum"}, "max")}};
  return {"line_tension", &s, readLineTension};
}

ProbeReader laplaceReader() {
  static const SchemaSection s{"probes.NAME (type: laplace)",
                               findProbeKindDescription("laplace"),
                               {probeTypeKey("laplace"),
                                selectorKey("nodes", "the nodes (inside the surface, at least 6 neighbours)"),
                                selectorKey("triangles", "the surface fitted"),
                                {"quantity",
                                 KeyType::Choice,
                                 "",
                                 "",
                                 "required",
                                 {},
                                 {},
                                 {"ratio", "simple_ratio", "radius", "tension", "pressure"},
                                 "what the probe reports"},
                                {"direction",
                                 KeyType::Vec3,
                                 "-",
                                 "",
                                 "required for simple_ratio, radius, tension",
                                 {},
                                 {},
                                 {},
                                 "the tangent direction of radius and tension (non-zero)"},
                                {"rings",
                                 KeyType::Integer,
                                 "",
                                 "2",
                                 "",
                                 KeyBound{1, true},
                                 KeyBound{20, true},
                                 {},
                                 "rings of neighbours the fit and average use"},
                                reduceKey({"value", "mean", "max", "min"}, "value")}};
  return {"laplace", &s, readLaplace};
}

ProbeReader foldsReader() {
  static const SchemaSection s{"probes.NAME (type: folds)",
                               findProbeKindDescription("folds"),
                               {probeTypeKey("folds"),
                                selectorKey("triangles", "the triangles"),
                                {"angle",
                                 KeyType::Number,
                                 "deg",
                                 "90",
                                 "",
                                 KeyBound{0, false},
                                 KeyBound{180, false},
                                 {},
                                 "the turn from the reference dihedral angle that counts as a fold"}}};
  return {"folds", &s, readFolds};
}

}  // namespace fsi::structure
