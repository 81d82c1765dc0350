#include "structure/elements/BarForces.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fsi::structure {

BarForces::BarForces(const Bars& bars, ElementDamping damping) : el_(bars), damping_(damping) {
  minDt_ = std::numeric_limits<double>::infinity();
  for (int e = 0; e < el_.count; ++e) {
    const double L0c = el_.restLength[e] * el_.invWaveSpeed[e];  // L0/c
    const double xi = damping_.bulkB1 + damping_.beta / L0c;     // damping ratio of the highest mode
    minDt_ = std::min(minDt_, L0c * (std::sqrt(1.0 + xi * xi) - xi));
  }
}

namespace {

template <bool Viscous, bool Energy>
void barBlock(const Bars& el, const BarBlock& blk, const ElementDamping& damping, ForceContext& ctx) {
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
    double N = blk.axialStiffness * eps;
    if constexpr (Energy) energy += 0.5 * N * eps * L0;
    const double iL = 1.0 / L;
    if constexpr (Viscous) {
      const double rate = ((v[3 * j] - v[3 * i]) * d[0] + (v[3 * j + 1] - v[3 * i + 1]) * d[1] +
                           (v[3 * j + 2] - v[3 * i + 2]) * d[2]) *
                          iL / L0;
      // ρ c = E/c with the bar's own (scaled) wave speed, as for cables (CableForces.cpp).
      N += (damping.beta + damping.bulkB1 * el.invWaveSpeed[e] * L0) * blk.axialStiffness * rate;
    }
    const double s = N * iL;
    for (int k = 0; k < 3; ++k) {
      f[3 * i + k] -= s * d[k];
      f[3 * j + k] += s * d[k];
    }
  }
  if constexpr (Energy) ctx.strainEnergy += energy;
}

template <bool Viscous>
void dispatchEnergy(const Bars& el, const BarBlock& b, const ElementDamping& damping, ForceContext& ctx) {
  ctx.wantEnergy ? barBlock<Viscous, true>(el, b, damping, ctx)
                 : barBlock<Viscous, false>(el, b, damping, ctx);
}

}  // namespace

void BarForces::addForces(ForceContext& ctx) const {
  for (const BarBlock& b : el_.blocks)
    damping_.enabled() ? dispatchEnergy<true>(el_, b, damping_, ctx)
                       : dispatchEnergy<false>(el_, b, damping_, ctx);
  ctx.minStableDt = std::min(ctx.minStableDt, minDt_);
}

void barForces(const Bars& el, const double* x, std::vector<double>& force, std::vector<double>& strain) {
  force.assign(std::size_t(el.count), 0.0);
  strain.assign(std::size_t(el.count), 0.0);
  for (const BarBlock& b : el.blocks)
    for (int e = b.begin; e < b.end; ++e) {
      const int i = el.conn[2 * e], j = el.conn[2 * e + 1];
      double L2 = 0;
      for (int k = 0; k < 3; ++k) L2 += (x[3 * j + k] - x[3 * i + k]) * (x[3 * j + k] - x[3 * i + k]);
      const double eps = (std::sqrt(L2) - el.restLength[e]) / el.restLength[e];
      strain[std::size_t(e)] = eps;
      force[std::size_t(e)] = b.axialStiffness * eps;
    }
}

}  // namespace fsi::structure
