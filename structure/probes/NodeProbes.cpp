// displacement and position: a component of the displacement x - X or of the position x of nodes.
#include <fmt/format.h>

#include <cmath>

#include "structure/probes/ProbeKinds.hpp"

namespace fsi::structure {

namespace {

void displacement(const ProbeSpec& p, ProbeState& state, std::vector<double>& vals) {
  const Nodes& N = state.model().nodes;
  for (int n : p.nodes) {
    const double u[3] = {N.x[3 * n] - N.X[3 * n], N.x[3 * n + 1] - N.X[3 * n + 1],
                         N.x[3 * n + 2] - N.X[3 * n + 2]};
    if (p.component == ProbeComponent::Radial) {
      double r = 0, r0 = 0;
      for (int k = 0; k < 3; ++k) {
        r += std::pow(N.x[3 * n + k] - p.center[k], 2);
        r0 += std::pow(N.X[3 * n + k] - p.center[k], 2);
      }
      vals.push_back(std::sqrt(r) - std::sqrt(r0));
    } else {
      vals.push_back(vectorComponent(u, p.component));
    }
  }
}

void position(const ProbeSpec& p, ProbeState& state, std::vector<double>& vals) {
  const Nodes& N = state.model().nodes;
  const bool radial = p.component == ProbeComponent::Radial;
  for (int n : p.nodes) {
    double r[3];
    for (int k = 0; k < 3; ++k) r[k] = N.x[3 * n + k] - (radial ? p.center[k] : 0.0);
    vals.push_back(vectorComponent(r, p.component));  // radial: the magnitude of x - center
  }
}

}  // namespace

ProbeKind displacementProbe() {
  return {"displacement", "a component of the displacement of a node (or reduced over nodes)", displacement};
}

ProbeKind positionProbe() {
  return {"position", "a component of the position of a node (or reduced over nodes)", position};
}

}  // namespace fsi::structure
