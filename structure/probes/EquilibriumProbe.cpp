// equilibrium_error: how far a state is from global equilibrium, |Σ_supports r + Σ_all f_ext| / |Σ_all f_ext|
// with r = f_int − f_ext the support reactions. The internal forces of every element sum to zero, so at a
// static state the supports carry exactly the applied load: this is 0 up to the run's static tolerance, and
// a loss of force in any element kernel or load (a force that does not sum to zero) shows here.
#include <cmath>

#include "structure/probes/ProbeKinds.hpp"

namespace fsi::structure {

namespace {

void evaluate(const ProbeSpec& p, ProbeState& state, std::vector<double>& vals) {
  const Nodes& N = state.model().nodes;
  double load[3] = {0, 0, 0}, sum[3] = {0, 0, 0};
  for (int n = 0; n < N.count; ++n)
    for (int k = 0; k < 3; ++k) load[k] += N.fext[3 * n + k];
  for (int k = 0; k < 3; ++k) sum[k] = load[k];
  const std::vector<double>& reaction = state.reactions();  // tie forces left out
  for (int n : p.nodes)
    for (int k = 0; k < 3; ++k) sum[k] += reaction[3 * n + k];
  const double L = std::sqrt(load[0] * load[0] + load[1] * load[1] + load[2] * load[2]);
  const double S = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
  vals.push_back(L > 0 ? S / L : S);
}

}  // namespace

ProbeKind equilibriumProbe() {
  return {"equilibrium_error",
          "|support reactions + applied load| / |applied load|: 0 at a static state (global equilibrium)",
          evaluate};
}

}  // namespace fsi::structure
