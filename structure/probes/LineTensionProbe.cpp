// line_tension: the elastic tension of a set of cables (suspension lines, brake lines), reduced over them:
// the largest line load, the brake-line load at a toggle, the mean tension of a row.
#include "structure/elements/CableForces.hpp"
#include "structure/probes/ProbeKinds.hpp"

namespace fsi::structure {

namespace {

const std::vector<std::string> kKeys{"type", "lines", "reduce"};

void parse(const YamlMap& p, const SetResolver& sets, ProbeSpec& spec) {
  spec.lines = sets.lines(p.required("lines"), p.childPath("lines"));
  spec.reduce = readReduce(p, {"max", "min", "mean", "sum"}, "max");
  p.finish(kKeys);
}

void evaluate(const ProbeSpec& p, ProbeState& state, std::vector<double>& vals) {
  const Model& m = *state.scene().model;
  std::vector<double> tension;
  cableTensions(m.cables, m.nodes.x.data(), tension);
  for (int e : p.lines) vals.push_back(tension[e]);
}

}  // namespace

ProbeKind lineTensionProbe() {
  return {"line_tension", kKeys, "the tension of a set of cables [N], reduced (max, min, mean, sum)", parse,
          evaluate};
}

}  // namespace fsi::structure
