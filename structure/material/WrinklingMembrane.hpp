#pragma once
// Plane-stress St Venant–Kirchhoff membrane law with the three-state wrinkling model (tension-field theory).
//
// Input is the Green–Lagrange strain (E11, E22, 2E12) in an element's in-plane frame; output is the second
// Piola–Kirchhoff stress (S11, S22, S12) in the same frame. The state is decided on principal strains:
//   slack    : major principal strain ε1 <= 0            -> S = 0
//   taut     : minor principal trial stress >= 0         -> S = C:E (isotropic plane stress)
//   wrinkled : otherwise, uniaxial stress along the major principal strain direction, S = Y ε1 n1⊗n1.
// The relaxed energy W(E) is continuous across all three states and S = dW/dE in each, so the law is
// hyperelastic and the energy bookkeeping stays exact with wrinkling switched on.

#include <cmath>
#include <cstdint>

namespace fsi::structure {

enum class WrinkleState : std::uint8_t { Taut = 0, Wrinkled = 1, Slack = 2 };

/// Isotropic plane-stress constants of one membrane material.
struct MembraneElasticity {
  double young = 0;    ///< Young's modulus Y [Pa]
  double poisson = 0;  ///< Poisson's ratio ν
  double c11() const { return young / (1.0 - poisson * poisson); }
};

/// Stress of a membrane that cannot carry compression. Returns the state; writes S (S11,S22,S12) and the
/// strain energy density per unit reference volume to `energy`.
inline WrinkleState wrinklingStress(double e11, double e22, double g12, double young, double c11, double nu,
                                    double S[3], double& energy) {
  const double em = 0.5 * (e11 + e22);
  const double hd = 0.5 * (e11 - e22);
  const double r2 = hd * hd + 0.25 * g12 * g12;  // squared radius of Mohr's circle of strain
  // Branch tests on squares: the square root is only needed in the wrinkled state.
  //   slack: e1 = em + r <= 0      <=>  em <= 0 and em² >= r²
  //   taut : e2 + ν e1 >= 0        <=>  (1+ν) em >= (1−ν) r  <=>  em >= 0 and (1+ν)² em² >= (1−ν)² r²
  if (em <= 0.0 && em * em >= r2) {
    S[0] = S[1] = S[2] = 0.0;
    energy = 0.0;
    return WrinkleState::Slack;
  }
  if (em >= 0.0 && (1.0 + nu) * (1.0 + nu) * em * em >= (1.0 - nu) * (1.0 - nu) * r2) {
    S[0] = c11 * (e11 + nu * e22);
    S[1] = c11 * (e22 + nu * e11);
    S[2] = 0.5 * c11 * (1.0 - nu) * g12;
    energy = 0.5 * (S[0] * e11 + S[1] * e22 + S[2] * g12);
    return WrinkleState::Taut;
  }
  // Wrinkled: r > 0 here (r = 0 with e1 > 0 would be equibiaxial tension, which is taut).
  const double r = std::sqrt(r2);
  const double e1 = em + r;
  const double s1 = young * e1;
  const double c2 = hd / r;         // cos 2θ of the major principal direction
  const double s2 = 0.5 * g12 / r;  // sin 2θ
  S[0] = 0.5 * s1 * (1.0 + c2);
  S[1] = 0.5 * s1 * (1.0 - c2);
  S[2] = 0.5 * s1 * s2;
  energy = 0.5 * s1 * e1;
  return WrinkleState::Wrinkled;
}

/// Plain St Venant–Kirchhoff plane stress (compression allowed), for materials with wrinkling switched off.
inline WrinkleState elasticStress(double e11, double e22, double g12, double c11, double nu, double S[3],
                                  double& energy) {
  S[0] = c11 * (e11 + nu * e22);
  S[1] = c11 * (e22 + nu * e11);
  S[2] = 0.5 * c11 * (1.0 - nu) * g12;
  energy = 0.5 * (S[0] * e11 + S[1] * e22 + S[2] * g12);
  return WrinkleState::Taut;
}

}  // namespace fsi::structure
