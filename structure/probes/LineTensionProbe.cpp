// line_tension: the elastic tension of a set of cables (suspension lines, brake lines), reduced over them:
// the largest line load, the brake-line load at a toggle, the mean tension of a row.
#include "structure/elements/CableForces.hpp"
#include "structure/probes/ProbeKinds.hpp"

namespace fsi::structure {

namespace {

void evaluate(const ProbeSpec& p, ProbeState& state, std::vector<double>& vals) {
  const Model& m = state.model();
  std::vector<double> tension;
  cableTensions(m.cables, m.nodes.x.data(), tension);
  for (int e : p.lines) vals.push_back(tension[e]);
}

}  // namespace

ProbeKind lineTensionProbe() {
  return {"line_tension", "the tension of a set of cables [N], reduced (max, min, mean, sum)", evaluate};
}

}  // namespace fsi::structure
