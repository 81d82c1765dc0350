#include "structure/elements/CableForces.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "structure/elements/AxialKernel.hpp"
#include "structure/elements/CableBatch.hpp"

namespace fsi::structure {

CableForces::CableForces(const Cables& cables, CableViscosity viscosity, CableKernel kernel)
    : el_(cables), visc_(viscosity), kernel_(kernel) {
  minDt_ = std::numeric_limits<double>::infinity();
  const double xi = visc_.bulkB1;  // β part depends on ω = 2c/L0 per element
  for (int e = 0; e < el_.count; ++e) {
    const double L = el_.restLength[e];
    const double xiE = xi + visc_.beta / (L * el_.invWaveSpeed[e]);
    minDt_ = std::min(minDt_, L * el_.invWaveSpeed[e] * (std::sqrt(1.0 + xiE * xiE) - xiE));
  }
  lanes_.first.resize(std::size_t(el_.count));
  lanes_.second.resize(std::size_t(el_.count));
  for (int e = 0; e < el_.count; ++e) {
    lanes_.first[std::size_t(e)] = 3 * el_.conn[2 * std::size_t(e)];
    lanes_.second[std::size_t(e)] = 3 * el_.conn[2 * std::size_t(e) + 1];
  }
  if (visc_.enabled()) {
    lanes_.viscous.resize(std::size_t(el_.count));
    for (const CableBlock& b : el_.blocks)
      for (int e = b.begin; e < b.end; ++e)
        lanes_.viscous[std::size_t(e)] =
            (visc_.beta + visc_.bulkB1 * el_.invWaveSpeed[e] * el_.restLength[e]) * b.axialStiffness;
  }
}

namespace {
// Cables go slack in compression: the shared axial kernel, tension only.
template <bool Viscous, bool Energy>
void cableBlock(const Cables& el, const CableBlock& blk, const CableViscosity& visc, ForceContext& ctx) {
  axial::addBlock<Viscous, Energy, true>(el, blk.begin, blk.end, blk.axialStiffness, visc.beta, visc.bulkB1,
                                         ctx);
}

// The batched kernel over the block's whole batches, the per-cable one over the remainder.
template <bool Viscous, bool Energy>
void batchedBlock(const Cables& el, const CableLanes& soa, const CableBlock& blk, const CableViscosity& visc,
                  ForceContext& ctx) {
  CableBlock rest = blk;
  rest.begin = cable::cableBatches<Viscous, Energy>(el, soa, blk, ctx);
  if (rest.begin < rest.end) cableBlock<Viscous, Energy>(el, rest, visc, ctx);
}

template <bool Viscous>
void dispatchEnergy(const Cables& el, const CableLanes& soa, const CableBlock& b, const CableViscosity& visc,
                    CableKernel kernel, ForceContext& ctx) {
  if (kernel == CableKernel::Batched) {
    ctx.wantEnergy ? batchedBlock<Viscous, true>(el, soa, b, visc, ctx)
                   : batchedBlock<Viscous, false>(el, soa, b, visc, ctx);
  } else {
    ctx.wantEnergy ? cableBlock<Viscous, true>(el, b, visc, ctx)
                   : cableBlock<Viscous, false>(el, b, visc, ctx);
  }
}

// Cables [begin, end) on the calling thread, block by block (one branch per block and step, none per cable).
void evaluateRange(const Cables& el, const CableLanes& soa, const CableViscosity& visc, CableKernel kernel,
                   int begin, int end, ForceContext& ctx) {
  for (const CableBlock& b : el.blocks) {
    CableBlock part = b;
    part.begin = std::max(b.begin, begin);
    part.end = std::min(b.end, end);
    if (part.begin >= part.end) continue;
    visc.enabled() ? dispatchEnergy<true>(el, soa, part, visc, kernel, ctx)
                   : dispatchEnergy<false>(el, soa, part, visc, kernel, ctx);
  }
}
}  // namespace

void CableForces::addForces(ForceContext& ctx) const {
  addRange(ctx, 0, el_.count);
}

void CableForces::addRange(ForceContext& ctx, int begin, int end) const {
  evaluateRange(el_, lanes_, visc_, kernel_, begin, end, ctx);
  ctx.minStableDt = std::min(ctx.minStableDt, minDt_);
}

Connectivity CableForces::connectivity() const {
  Connectivity c;
  c.items = el_.count;
  c.nodesPerItem = 2;
  c.nodes = el_.conn.data();
  c.batch = kernel_ == CableKernel::Batched ? cable::kWidth : 1;
  c.scattered = true;
  return c;
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
