// reaction_moment: a component of the moment about a point of the reaction forces (internal minus external
// force) on a set of nodes, Σ (x_i − about) × r_i at the current positions — e.g. the moment the anchored
// confluence point takes, whose change shows what a brake input does. `about` is a point [x, y, z] or a set
// of one node (e.g. wing/confluence: the moments about the anchor), taken at its reference position.
#include "structure/probes/ProbeKinds.hpp"

namespace fsi::structure {

namespace {

void evaluate(const ProbeSpec& p, ProbeState& state, std::vector<double>& vals) {
  const Nodes& N = state.model().nodes;
  const std::vector<double>& reaction = state.reactions();  // tie forces left out
  double m[3] = {0, 0, 0};
  for (int n : p.nodes) {
    double d[3], r[3];
    for (int k = 0; k < 3; ++k) {
      d[k] = N.x[3 * n + k] - p.center[k];
      r[k] = reaction[3 * n + k];
    }
    m[0] += d[1] * r[2] - d[2] * r[1];
    m[1] += d[2] * r[0] - d[0] * r[2];
    m[2] += d[0] * r[1] - d[1] * r[0];
  }
  vals.push_back(vectorComponent(m, p.component));
}

}  // namespace

ProbeKind reactionMomentProbe() {
  return {"reaction_moment", "a component of the moment of the reaction forces of a set of nodes [N m]",
          evaluate};
}

}  // namespace fsi::structure
