// pitch_angle: the angle [deg] in the x-z plane of the chord from one node set (the leading edge, mean
// position) to another (the trailing edge), positive nose-up: atan2(z_from − z_to, x_to − x_from). x is the
// chord direction of the design shape (the air flows towards +x), so the design chord has the angle of its
// incidence; a canopy pitching back under line drag shows as the angle falling.
#include <cmath>

#include "structure/probes/ProbeKinds.hpp"

namespace fsi::structure {

namespace {

void mean(const Nodes& N, const std::vector<int>& nodes, double c[3]) {
  c[0] = c[1] = c[2] = 0;
  for (int n : nodes)
    for (int k = 0; k < 3; ++k) c[k] += N.x[3 * n + k] / double(nodes.size());
}

void evaluate(const ProbeSpec& p, ProbeState& state, std::vector<double>& vals) {
  const Nodes& N = state.model().nodes;
  double a[3], b[3];
  mean(N, p.nodes, a);
  mean(N, p.nodesTo, b);
  vals.push_back(std::atan2(a[2] - b[2], b[0] - a[0]) * 180.0 / 3.14159265358979323846);
}

}  // namespace

ProbeKind pitchAngleProbe() {
  return {"pitch_angle", "nose-up angle [deg] in the x-z plane of the chord from one node set to another",
          evaluate};
}

}  // namespace fsi::structure
