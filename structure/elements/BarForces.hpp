#pragma once
// BarForces: the bars' internal forces. Engineering strain ε = (L − L0)/L0, axial force N = EA ε (tension and
// compression) plus (β + b1 L0/c) EA ε̇ with the element damping, strain energy ½ EA ε² L0. Stable step
// L0/c (sqrt(1 + ξ²) − ξ), ξ = b1 + β c/L0, c = sqrt(E/ρ) (the bar's own after mass scaling: construct after
// it). One loop per material block, templated on damping and energy (no branch, no virtual call per bar).

#include <vector>

#include "structure/effects/Effect.hpp"
#include "structure/elements/BarElement.hpp"

namespace fsi::structure {

class BarForces final : public Effect {
 public:
  BarForces(const Bars& bars, ElementDamping damping);
  std::string name() const override { return "bar"; }
  void addForces(ForceContext& ctx) const override;

 private:
  const Bars& el_;
  ElementDamping damping_;
  double minDt_ = 0;  ///< depends only on reference data: computed once
};

/// Elastic axial force [N] (tension positive) and strain of every bar at configuration x.
void barForces(const Bars& bars, const double* x, std::vector<double>& force, std::vector<double>& strain);

}  // namespace fsi::structure
