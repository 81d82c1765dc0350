// projected_diameter: the diameter of a surface seen along a direction (a canopy's projected diameter D_p):
// twice the largest distance of its nodes from the axis through their centroid along the direction.
#include <algorithm>
#include <cmath>

#include "structure/probes/ProbeKinds.hpp"

namespace fsi::structure {

namespace {

void evaluate(const ProbeSpec& p, ProbeState& state, std::vector<double>& vals) {
  const Model& m = state.model();
  const double* x = m.nodes.x.data();
  std::vector<int> nodes;
  for (int t : p.triangles)
    for (int k = 0; k < 3; ++k) nodes.push_back(m.membranes.conn[3 * t + k]);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  const double* d = p.direction.data();
  const double dl = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  double c[3] = {0, 0, 0};
  for (int n : nodes)
    for (int k = 0; k < 3; ++k) c[k] += x[3 * n + k] / double(nodes.size());
  double far = 0;
  for (int n : nodes) {
    double r[3], along = 0;
    for (int k = 0; k < 3; ++k) r[k] = x[3 * n + k] - c[k], along += r[k] * d[k] / dl;
    double s = 0;
    for (int k = 0; k < 3; ++k) s += std::pow(r[k] - along * d[k] / dl, 2);
    far = std::max(far, s);
  }
  vals.push_back(2.0 * std::sqrt(far));
}

}  // namespace

ProbeKind projectedDiameterProbe() {
  return {"projected_diameter",
          "twice the largest distance of a surface's nodes from the axis along `direction` through their "
          "centroid (a canopy's projected diameter)",
          evaluate};
}

}  // namespace fsi::structure
