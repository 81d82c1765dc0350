// stress: the maximum or minimum principal membrane stress of a set of triangles, reduced over them (the
// mean weighted by the current areas).
#include <cmath>

#include "structure/probes/ProbeKinds.hpp"

namespace fsi::structure {

namespace {

void evaluate(const ProbeSpec& p, ProbeState& state, std::vector<double>& vals) {
  const MembraneStressField& stress = state.membraneStress();
  // principal holds (max, min) per element.
  const int which = p.quantity == StressQuantity::MinPrincipal ? 1 : 0;
  if (!p.areaWeighted) {
    for (int e : p.triangles) vals.push_back(stress.principal[2 * e + which]);
    return;
  }
  const Model& model = state.model();
  const std::vector<double>& x = model.nodes.x;
  const std::size_t first = vals.size();
  double total = 0;
  for (int e : p.triangles) {
    const int* c = &model.membranes.conn[3 * e];
    double u[3], v[3];
    for (int k = 0; k < 3; ++k) {
      u[k] = x[3 * c[1] + k] - x[3 * c[0] + k];
      v[k] = x[3 * c[2] + k] - x[3 * c[0] + k];
    }
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double a = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    vals.push_back(a * stress.principal[2 * e + which]);
    total += a;
  }
  for (std::size_t i = first; i < vals.size(); ++i) vals[i] /= total;
}

}  // namespace

ProbeKind stressProbe() {
  return {"stress", "the max or min principal membrane stress over a set of triangles", evaluate};
}

}  // namespace fsi::structure
