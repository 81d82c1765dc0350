#pragma once
// Energy bookkeeping of a run. The balance W_ext = ΔKE + W_int + D_mass holds for any exact solution; the
// central-difference scheme keeps it to O(Δt²). A growing error is the signature of an unstable step.

#include <algorithm>
#include <cmath>

namespace fsi::structure {

struct EnergyLedger {
  double kinetic = 0;         ///< ½ v·M v at the last integer step
  double initialKinetic = 0;  ///< kinetic energy at t0
  double strain = 0;          ///< elastic strain energy (at the last monitoring step)
  double externalWork = 0;    ///< ∫ f_ext·dx, including the work of prescribed-motion reactions
  double internalWork = 0;    ///< ∫ f_int·dx = strain energy + viscous (β, bulk) dissipation
  double massDamping = 0;     ///< dissipation of the α (mass-proportional) damping

  double viscousDissipation() const { return internalWork - strain; }
  double scale() const {
    return std::max({std::abs(externalWork), std::abs(internalWork) + kinetic + massDamping, initialKinetic});
  }
  /// |W_ext + KE0 − KE − W_int − D| relative to the largest energy in play (0 while nothing moves).
  double balanceError() const {
    const double s = scale();
    if (!(s > 0)) return 0.0;
    return std::abs(externalWork + initialKinetic - kinetic - internalWork - massDamping) / s;
  }
};

}  // namespace fsi::structure
