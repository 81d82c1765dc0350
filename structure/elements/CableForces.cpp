#include "structure/elements/CableForces.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fsi::structure {

CableForces::CableForces(const Cables& cables, CableViscosity viscosity) : el_(cables), visc_(viscosity) {
  minDt_ = std::numeric_limits<double>::infinity();
  const double xi = visc_.bulkB1;  // β part depends on ω = 2c/L0 per element
  for (int e = 0; e < el_.count; ++e) {
    const double L = el_.restLength[e];
    const double xiE = xi + visc_.beta / (L * el_.invWaveSpeed[e]);
    minDt_ = std::min(minDt_, L * el_.invWaveSpeed[e] * (std::sqrt(1.0 + xiE * xiE) - xiE));
  }
}

namespace {
template <bool Viscous, bool Energy>
void cableBlock(const Cables& el, const CableBlock& blk, const CableViscosity& visc, ForceContext& ctx) {
  const double* __restrict x = ctx.x;
  const double* __restrict v = ctx.v;
  double* __restrict f = ctx.fint;
  double energy = 0;
  for (int e = blk.begin; e < blk.end; ++e) {
    const int i = el.conn[2 * e], j = el.conn[2 * e + 1];
    const double d[3] = {x[3 * j] - x[3 * i], x[3 * j + 1] - x[3 * i + 1], x[3 * j + 2] - x[3 * i + 2]};
    const double L = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const double L0 = el.restLength[e];
    const double eps = (L - L0) / L0;
    double T = blk.axialStiffness * std::max(0.0, eps);
    if constexpr (Energy) energy += 0.5 * T * std::max(0.0, eps) * L0;
    const double iL = 1.0 / L;
    if constexpr (Viscous) {
      const double rate = ((v[3 * j] - v[3 * i]) * d[0] + (v[3 * j + 1] - v[3 * i + 1]) * d[1] +
                           (v[3 * j + 2] - v[3 * i + 2]) * d[2]) *
                          iL / L0;
      // Bulk viscosity b1 ρ c A L0 ε̇ with the element's own ρ and c: c² = E/ρ gives ρ c = E/c = E ·
      // invWaveSpeed, which stays right when mass scaling raised ρ by s (and lowered c). The unscaled ρ would
      // give a scaled cable the damping ratio b1/s instead of the b1 its damped stable step assumes.
      T += (visc.beta + visc.bulkB1 * el.invWaveSpeed[e] * L0) * blk.axialStiffness * rate;
    }
    const double s = T * iL;
    for (int k = 0; k < 3; ++k) {
      f[3 * i + k] -= s * d[k];
      f[3 * j + k] += s * d[k];
    }
  }
  if constexpr (Energy) ctx.strainEnergy += energy;
}
}  // namespace

void CableForces::addForces(ForceContext& ctx) const {
  for (const CableBlock& b : el_.blocks) {
    if (visc_.enabled()) {
      ctx.wantEnergy ? cableBlock<true, true>(el_, b, visc_, ctx)
                     : cableBlock<true, false>(el_, b, visc_, ctx);
    } else {
      ctx.wantEnergy ? cableBlock<false, true>(el_, b, visc_, ctx)
                     : cableBlock<false, false>(el_, b, visc_, ctx);
    }
  }
  ctx.minStableDt = std::min(ctx.minStableDt, minDt_);
}

void CableForces::evaluate(const double* x, std::vector<double>& tension) const {
  cableTensions(el_, x, tension);
}

void cableTensions(const Cables& el, const double* x, std::vector<double>& tension) {
  tension.assign(el.count, 0.0);
  for (const CableBlock& b : el.blocks)
    for (int e = b.begin; e < b.end; ++e) {
      const int i = el.conn[2 * e], j = el.conn[2 * e + 1];
      double L2 = 0;
      for (int k = 0; k < 3; ++k) L2 += (x[3 * j + k] - x[3 * i + k]) * (x[3 * j + k] - x[3 * i + k]);
      tension[e] = b.axialStiffness * std::max(0.0, (std::sqrt(L2) - el.restLength[e]) / el.restLength[e]);
    }
}

}  // namespace fsi::structure
