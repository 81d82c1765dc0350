#include "structure/run/InstabilityDiagnosis.hpp"

#include <fmt/format.h>

#include <cmath>

#include "structure/effects/MembraneForces.hpp"

namespace fsi::structure {

std::string diagnoseInstability(const Scene& scene, const CentralDifference& cd, long goodSteps,
                                double goodTime, bool nonFinite) {
  const Model& m = *scene.model;
  const Nodes& N = m.nodes;
  std::string s = fmt::format("instability at step {} (t = {:.6g} s): ", cd.steps(), cd.time());
  int firstBad = -1, badCount = 0, fastest = 0;
  double vmax = -1;
  for (int i = 0; i < N.count; ++i) {
    bool finite = true;
    double v2 = 0;
    for (int k = 0; k < 3; ++k) {
      finite = finite && std::isfinite(N.x[3 * i + k]) && std::isfinite(N.v[3 * i + k]);
      v2 += N.v[3 * i + k] * N.v[3 * i + k];
    }
    if (!finite) {
      if (firstBad < 0) firstBad = i;
      ++badCount;
    } else if (v2 > vmax) {
      vmax = v2, fastest = i;
    }
  }
  if (nonFinite && firstBad >= 0) {
    s += fmt::format("non-finite state at {} node(s), first {}. ", badCount, m.describeNode(firstBad));
  } else {
    s += fmt::format("energy balance error {:.3g} exceeds the tolerance; fastest {} (|v| = {:.3g} m/s). ",
                     cd.energy().balanceError(), m.describeNode(fastest), std::sqrt(vmax));
  }
  if (scene.membrane) {
    MembraneStressField f;
    scene.membrane->evaluate(N.x.data(), f);
    int worst = -1;
    double worstStrain = -1;
    for (int e = 0; e < m.membranes.count; ++e) {
      const double es = f.majorStrain[e];
      if (!std::isfinite(es)) {
        worst = e;
        break;
      }
      if (es > worstStrain) worstStrain = es, worst = e;
    }
    if (worst >= 0)
      s += std::isfinite(f.majorStrain[worst])
               ? fmt::format("Most strained element: {} (major strain {:.3g}). ", m.describeTriangle(worst),
                             f.majorStrain[worst])
               : fmt::format("First element with a non-finite strain: {}. ", m.describeTriangle(worst));
  }
  s += fmt::format(
      "Step used {:.4g} s, element stability estimate {:.4g} s. Last stable state: step {} "
      "(t = {:.6g} s).",
      cd.lastDt(), cd.stableDt(), goodSteps, goodTime);
  return s;
}

}  // namespace fsi::structure
