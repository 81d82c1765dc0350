#pragma once
// The axial two-node kernel that cables and bars share: strain from the current length, the axial force of a
// linear law (TensionOnly: a cable's, zero in compression; otherwise a bar's), optional viscous damping (the
// material's beta and the bulk viscosity b1 rho c A L0 of the element's own, possibly mass-scaled, wave
// speed) and the strain energy, scattered into the nodal forces. One loop per block, no branch per element.

#include <algorithm>
#include <cmath>

#include "structure/effects/Effect.hpp"

namespace fsi::structure::axial {

/// Elements [begin, end) of `el` (conn, restLength, invWaveSpeed per element) with the block's axial
/// stiffness E·A; beta, bulkB1 the damping coefficients (used only when Viscous).
template <bool Viscous, bool Energy, bool TensionOnly, class Elements>
void addBlock(const Elements& el, int begin, int end, double axialStiffness, double beta, double bulkB1,
              ForceContext& ctx) {
  const double* __restrict x = ctx.x;
  const double* __restrict v = ctx.v;
  double* __restrict f = ctx.fint;
  double energy = 0;
  for (int e = begin; e < end; ++e) {
    const int i = el.conn[2 * e], j = el.conn[2 * e + 1];
    const double d[3] = {x[3 * j] - x[3 * i], x[3 * j + 1] - x[3 * i + 1], x[3 * j + 2] - x[3 * i + 2]};
    const double L = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const double L0 = el.restLength[e];
    const double eps = (L - L0) / L0;
    const double strain = TensionOnly ? std::max(0.0, eps) : eps;
    double N = axialStiffness * strain;
    if constexpr (Energy) energy += 0.5 * N * strain * L0;
    const double iL = 1.0 / L;
    if constexpr (Viscous) {
      const double rate = ((v[3 * j] - v[3 * i]) * d[0] + (v[3 * j + 1] - v[3 * i + 1]) * d[1] +
                           (v[3 * j + 2] - v[3 * i + 2]) * d[2]) *
                          iL / L0;
      // Bulk viscosity b1 rho c A L0 eps' with the element's own rho and c: c^2 = E/rho gives rho c = E/c =
      // E * invWaveSpeed, which stays right when mass scaling raised rho by s (and lowered c). The unscaled
      // rho would give a scaled element the damping ratio b1/s instead of the b1 its damped stable step
      // assumes.
      N += (beta + bulkB1 * el.invWaveSpeed[e] * L0) * axialStiffness * rate;
    }
    const double s = N * iL;
    for (int k = 0; k < 3; ++k) {
      f[3 * i + k] -= s * d[k];
      f[3 * j + k] += s * d[k];
    }
  }
  if constexpr (Energy) ctx.strainEnergy += energy;
}

}  // namespace fsi::structure::axial
