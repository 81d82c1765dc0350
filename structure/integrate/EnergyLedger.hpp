#pragma once
// Energy bookkeeping of a central-difference run, exact at every step.
//
// The velocity update M(v(n+½) − v(n−½)) = Δ(n)·G(n) (G: every force at step n, damping and support
// reactions included; Δ(n) = ½(Δt(n) + Δt(n+1))) gives, dotted with v(n∓½), the identity
//   KE×(n) = ½ v(n−½)·M v(n+½),   KE×(n) − KE×(n−1) = ½Δ(n−1) G(n−1)·v(n−½) + ½Δ(n) G(n)·v(n−½).
// So the product-form kinetic energy KE× balances, to round-off at every step, the work booked in two
// halves per force evaluation: ½Δ(n) G(n)·v(n−½) at step n and ½Δ(n) G(n)·v(n+½) ("pending") at step
// n + 1. For a constant step these halves add up to the trapezoidal work ∫f·dx through x(n). The half-step
// start (v(−½) = v(0)) enters as a modified initial kinetic energy KE(0) − ½ δv·M δv, δv = v(½) − v(0),
// which makes the booked work the trapezoidal work from x(0) as well. For an undamped linear system
// KE×(n) + U(x(n)) is the energy the leapfrog conserves exactly.
//
// Being an identity, the balance cannot reveal an unstable step; it checks that every force's work is
// booked (a missing support reaction, a constraint pass, a non-finite state). Instability shows in the
// energy of the step-to-step velocity change, δ = KE(n) − KE×(n) = ⅛ Δv·M Δv (KE: the physical kinetic
// energy ½ v̄·M v̄ of the mid-step velocity v̄ = ½(v(n−½) + v(n+½))): per mode of a linear system
// δ = (ω Δt / 2)² U_mode, bounded by the mode's energy while ωΔt < 2 and growing without bound beyond.
// growth() compares δ with the energy ever supplied to the structure.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace fsi::structure {

struct EnergyLedger {
  double kinetic = 0;         ///< physical ½ v̄·M v̄ at the last integer step (v̄: mid-step velocity)
  double kineticProduct = 0;  ///< KE× = ½ v(n−½)·M v(n+½) at the last integer step
  double initialKinetic = 0;  ///< ½ v·M v at t0 (or at the restored half step)
  double startKick = 0;       ///< ½ δv·M δv of the half-step start (see above); 0 without one
  double strain = 0;          ///< elastic strain energy (at the last monitoring step)
  double initialStrain = 0;   ///< strain energy at t0 (a pre-stressed start releases it as work)
  double externalWork = 0;    ///< applied loads and support reactions (prescribed motions, sliding planes)
  double internalWork = 0;    ///< ∫ f_int·dx = strain energy change + viscous (β, bulk) dissipation
  double massDamping = 0;     ///< dissipation of the α (mass-proportional) damping
  /// Second halves of the last force evaluation's work (booked with the next step).
  double pendingExt = 0, pendingInt = 0, pendingDamp = 0;
  /// Largest energy supplied so far: KE0 + U0 + max |W_ext| (the stored strain energy U0 is all the
  /// elements can give back; their work W_int is no bound once a step is unstable, its quadrature fails).
  double supplied = 0;
  double maxGrowth = 0;    ///< largest growth() seen
  double createdLast = 0;  ///< created() at the last step that evaluated the strain energy
  double maxCreated = 0;   ///< largest of those

  /// Every field, in declaration order: what a restart state stores so the bookkeeping continues exactly.
  static constexpr int kFields = 16;
  std::array<double, kFields> values() const {
    return {kinetic,      kineticProduct, initialKinetic, startKick,  strain,     initialStrain,
            externalWork, internalWork,   massDamping,    pendingExt, pendingInt, pendingDamp,
            supplied,     maxGrowth,      createdLast,    maxCreated};
  }
  void setValues(const std::array<double, kFields>& a) {
    double* f[kFields] = {&kinetic,     &kineticProduct, &initialKinetic, &startKick,
                          &strain,      &initialStrain,  &externalWork,   &internalWork,
                          &massDamping, &pendingExt,     &pendingInt,     &pendingDamp,
                          &supplied,    &maxGrowth,      &createdLast,    &maxCreated};
    for (int i = 0; i < kFields; ++i) *f[i] = a[std::size_t(i)];
  }

  /// W_int − (U − U0): the viscous (β, bulk) dissipation.
  double viscousDissipation() const { return internalWork - (strain - initialStrain); }
  /// The largest energy in play, the energy supplied so far included (at the first step the work booked is
  /// round-off while the pending half already carries the energy a load or a support puts in).
  double scale() const {
    return std::max({std::abs(externalWork), std::abs(internalWork) + std::abs(kineticProduct) + massDamping,
                     initialKinetic, supplied});
  }
  /// |W_ext + KE0 − ½δv·Mδv − KE× − W_int − D| relative to the largest energy in play (0 while nothing
  /// moves). Round-off when every force's work is booked.
  double balanceError() const {
    const double s = scale();
    if (!(s > 0)) return 0.0;
    return std::abs(externalWork + initialKinetic - startKick - kineticProduct - internalWork - massDamping) /
           s;
  }
  /// The same balance with the physical kinetic energy KE of the mid-step velocity in place of KE×: the
  /// leapfrog's O(Δt²) departure from the energy of the exact solution (an accuracy measure, not a check).
  double physicalBalanceError() const {
    const double s = std::max(scale(), kinetic);
    if (!(s > 0)) return 0.0;
    return std::abs(externalWork + initialKinetic - kinetic - internalWork - massDamping) / s;
  }
  /// Energy of the step-to-step velocity change over the energy supplied to the structure. A stable step
  /// keeps it below (ωΔt/2)²/(1 − (ωΔt/2)²) ≤ 4.3 at ωΔt ≤ 1.8 even with all the energy in the highest mode
  /// (typically ≪ 1); it grows geometrically once a mode is unstable.
  double growth() const {
    const double d = kinetic - kineticProduct;
    if (!(d > 0)) return 0.0;
    return supplied > 0 ? d / supplied : std::numeric_limits<double>::infinity();
  }
  /// Strain energy gained beyond the internal work booked, U − U0 − W_int, over the energy supplied: the
  /// energy the integration created in the elements. A hyperelastic element cannot hold more than the work
  /// done on it (viscosity only dissipates), so in a stable run this is the trapezoidal rule's O(Δt²) error;
  /// an unstable step drives it up. Valid when `strain` is current (steps that evaluated it).
  double created() const {
    const double c = strain - initialStrain - internalWork;
    if (!std::isfinite(c)) return std::numeric_limits<double>::infinity();
    return supplied > 0 ? std::max(c, 0.0) / supplied : 0.0;
  }
  /// Updates `supplied` and `maxGrowth` after a step (called by the integrator).
  void updateSupplied() {
    const double ext = std::max(std::abs(externalWork), std::abs(externalWork + pendingExt));
    supplied = std::max(supplied, initialKinetic + std::max(initialStrain, 0.0) + ext);
    const double g = growth();
    if (g > maxGrowth || !std::isfinite(g)) maxGrowth = g;
  }
};

/// A growth() above this stops a run as unstable: ten times the energy ever supplied to the structure sits
/// in the step-to-step velocity change, which a stable step cannot produce (see growth()).
inline constexpr double kGrowthLimit = 10.0;

}  // namespace fsi::structure
