#pragma once
// The cable force kernel on batches of lanes::kWidth cables at once (structure-of-arrays lanes).
//
// Same element as the per-cable kernel in CableForces.cpp (which stays as the reference and handles the
// batch remainder): gather the two end nodes of each lane into x, y, z lane vectors (by their offsets,
// 3 × node index, laid out at construction: no index arithmetic in the loop), compute the length, the
// strain, the tension-only tension (a max with zero per lane, so a slack lane gives zero elastic force with
// no branch), the viscous term and the force s d for all lanes together, then scatter-add the nodal forces
// lane by lane (lanes may share nodes: a chain of cables does, so the scatter is sequential, all first ends
// then all second ends). The arithmetic is the per-cable kernel's, operation for operation; differences are
// round-off only (fused multiply-adds placed differently, the order of the additions at a node, energy
// summed per lane); tests/unit/test_cable_batch.cpp checks them against a plain per-cable evaluation.

#include "structure/effects/Effect.hpp"
#include "structure/elements/CableForces.hpp"
#include "structure/model/Lanes.hpp"
#include "structure/model/Model.hpp"

namespace fsi::structure::cable {

using lanes::kWidth;
using lanes::Vd;

/// Batched kernel over the whole batches of [blk.begin, blk.end); returns the first cable it did not evaluate
/// (the remainder, fewer than kWidth cables, is left to the per-cable kernel). Adds forces to ctx.fint and
/// (Energy) the strain energy to ctx.strainEnergy exactly like the per-cable kernel.
template <bool Viscous, bool Energy>
int cableBatches(const Cables& el, const CableLanes& soa, const CableBlock& blk, ForceContext& ctx) {
  const int nBatches = (blk.end - blk.begin) / kWidth;
  const int stop = blk.begin + nBatches * kWidth;
  if (nBatches == 0) return blk.begin;
  const double* __restrict x = ctx.x;
  const double* __restrict v = ctx.v;
  double* __restrict f = ctx.fint;
  const int* first = soa.first.data();
  const int* second = soa.second.data();
  const double* rest = el.restLength.data();
  const double* coefficient = soa.viscous.data();
  const Vd zero = lanes::splat(0.0);
  const double ea = blk.axialStiffness;
  Vd energy = zero;

  for (int e = blk.begin; e < stop; e += kWidth) {
    const int* ni = first + e;
    const int* nj = second + e;
    Vd xi[3], xj[3];
    lanes::gather3Offsets(x, ni, xi);
    lanes::gather3Offsets(x, nj, xj);
    Vd d[3];
    for (int k = 0; k < 3; ++k) d[k] = xj[k] - xi[k];
    const Vd L = lanes::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const Vd L0 = lanes::load(rest + e);
    const Vd eps = (L - L0) / L0;
    const Vd taut = lanes::max(zero, eps);  // tension only: 0 on a slack lane
    Vd T = ea * taut;
    if constexpr (Energy) energy += 0.5 * T * taut * L0;
    const Vd iL = 1.0 / L;
    if constexpr (Viscous) {
      Vd vi[3], vj[3];
      lanes::gather3Offsets(v, ni, vi);
      lanes::gather3Offsets(v, nj, vj);
      const Vd rate = ((vj[0] - vi[0]) * d[0] + (vj[1] - vi[1]) * d[1] + (vj[2] - vi[2]) * d[2]) * iL / L0;
      T += lanes::load(coefficient + e) * rate;
    }
    const Vd s = T * iL;
    Vd fi[3], fj[3];
    for (int k = 0; k < 3; ++k) {
      fj[k] = s * d[k];
      fi[k] = -fj[k];
    }
    lanes::scatterAdd3Offsets(f, ni, fi);
    lanes::scatterAdd3Offsets(f, nj, fj);
  }
  if constexpr (Energy) ctx.strainEnergy += lanes::sum(energy);
  return stop;
}

}  // namespace fsi::structure::cable
