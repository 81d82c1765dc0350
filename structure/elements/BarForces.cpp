#include "structure/elements/BarForces.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "structure/elements/AxialKernel.hpp"

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

// Bars carry compression: the shared axial kernel with the linear law both ways.
template <bool Viscous, bool Energy>
void barBlock(const Bars& el, const BarBlock& blk, const ElementDamping& damping, ForceContext& ctx) {
  axial::addBlock<Viscous, Energy, false>(el, blk.begin, blk.end, blk.axialStiffness, damping.beta,
                                          damping.bulkB1, ctx);
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
