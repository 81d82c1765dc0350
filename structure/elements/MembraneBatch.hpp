#pragma once
// The membrane force kernel on batches of lanes::kWidth triangles at once (structure-of-arrays lanes).
//
// Same element as the per-element kernel in MembraneForces.cpp (which stays as the reference and handles the
// batch remainder): gather the three nodes of each lane into lane vectors, compute F, C, the wrinkling law,
// the stable step and P = F S for all lanes together, then scatter-add the nodal forces lane by lane (lanes
// may share nodes, so the scatter is sequential, in element order as in the per-element kernel). The law's
// three states are computed for every lane and chosen with blends: no branch depends on an element, so the
// compiler keeps every lane in one vector register. Differences to the per-element kernel are round-off only
// (fused multiply-adds placed differently, 1/r computed once, energy summed per lane);
// tests/unit/test_membrane_batch.cpp checks them against it.

#include <cmath>

#include "structure/effects/Effect.hpp"
#include "structure/elements/ElementKind.hpp"
#include "structure/model/Lanes.hpp"
#include "structure/model/Model.hpp"

namespace fsi::structure::membrane {

using lanes::kWidth;
using lanes::Vd;
using lanes::Vm;

/// Batched kernel over the whole batches of [blk.begin, blk.end); returns the first element it did not
/// evaluate (the remainder, fewer than kWidth elements, is left to the per-element kernel). Adds forces to
/// ctx.fint, lowers ctx.minStableDt and (Energy) adds to ctx.strainEnergy exactly like the per-element
/// kernel.
/// How many triangles ahead the kernel asks for the nodes' coordinates and forces of its first lane (beyond
/// the L2 cache at 10⁵ triangles the gathers wait on them; a prefetch changes no result).
constexpr int kAhead = 128;

template <bool Wrinkling, bool Viscous, bool Energy>
int membraneBatches(const MembraneTriangles& el, const MembraneBlock& blk, const ElementDamping& visc,
                    ForceContext& ctx) {
  const int nBatches = (blk.end - blk.begin) / kWidth;
  const int stop = blk.begin + nBatches * kWidth;
  if (nBatches == 0) return blk.begin;
  const double* __restrict x = ctx.x;
  const double* __restrict v = ctx.v;
  double* __restrict f = ctx.fint;
  const int* conn = el.conn.data();
  const double* geo = el.geo.data();
  const double* iws = el.invWaveSpeed.data();
  const double* refStep2 = el.refStep2.data();

  const double nu = blk.poisson, c11 = blk.c11, young = blk.young;
  const double stiffA = 1.0 + 0.5 * (1.0 + nu), stiffB = 0.5 * (1.0 + nu);
  const double tautA = (1.0 + nu) * (1.0 + nu), tautB = (1.0 - nu) * (1.0 - nu);
  // Stable step as in the per-element kernel: a running minimum of Δt² = num/den per lane (no division per
  // element), or the damped step's plain minimum.
  double num0 = ctx.minStableDt * ctx.minStableDt, den0 = 1.0;
  if (!std::isfinite(num0)) num0 = 1.0, den0 = 0.0;
  Vd bestNum = lanes::splat(num0), bestDen = lanes::splat(den0);
  Vd minDt = lanes::splat(ctx.minStableDt);
  Vd energy = lanes::splat(0.0);
  const Vd zero = lanes::splat(0.0), one = lanes::splat(1.0);

  for (int e = blk.begin; e < stop; e += kWidth) {
    // Gather: node indices, node coordinates and reference geometry of every lane.
    int n[3][kWidth];
    for (int l = 0; l < kWidth; ++l)
      for (int a = 0; a < 3; ++a) n[a][l] = conn[3 * (e + l) + a];
    Vd p[3][3];  // node a, component i
    for (int a = 0; a < 3; ++a) lanes::gather3(x, n[a], p[a]);
    if (e + kAhead < stop)
      for (int a = 0; a < 3; ++a) {
        const int far = conn[3 * (e + kAhead) + a];
        __builtin_prefetch(&x[3 * far]);
        __builtin_prefetch(&f[3 * far], 1);
      }
    Vd g[MembraneTriangles::kGeo];
    lanes::loadRecords<MembraneTriangles::kGeo>(geo + MembraneTriangles::kGeo * e, g);
    // Kinematics (membrane::kinematics lane by lane).
    const Vd n2x = g[0], n2y = -g[1] * g[0] * g[2], n3y = g[2], tA0 = g[3];
    Vd d21[3], d31[3], f1[3], f2[3];
    for (int i = 0; i < 3; ++i) {
      d21[i] = p[1][i] - p[0][i];
      d31[i] = p[2][i] - p[0][i];
      f1[i] = d21[i] * n2x;
      f2[i] = d21[i] * n2y + d31[i] * n3y;
    }
    const Vd C11 = f1[0] * f1[0] + f1[1] * f1[1] + f1[2] * f1[2];
    const Vd C12 = f1[0] * f2[0] + f1[1] * f2[1] + f1[2] * f2[2];
    const Vd C22 = f2[0] * f2[0] + f2[1] * f2[1] + f2[2] * f2[2];
    // The law (wrinklingStress / elasticStress): every state computed, the lane's own chosen by blends.
    const Vd e11 = 0.5 * (C11 - 1.0), e22 = 0.5 * (C22 - 1.0), g12 = C12;
    Vd S0 = c11 * (e11 + nu * e22);
    Vd S1 = c11 * (e22 + nu * e11);
    Vd S2 = 0.5 * c11 * (1.0 - nu) * g12;
    Vd w = 0.5 * (S0 * e11 + S1 * e22 + S2 * g12);
    if constexpr (Wrinkling) {
      const Vd em = 0.5 * (e11 + e22);
      const Vd hd = 0.5 * (e11 - e22);
      const Vd r2 = hd * hd + 0.25 * g12 * g12;
      const Vm slack = (em <= 0.0) & (em * em >= r2);
      const Vm taut = (em >= 0.0) & (tautA * em * em >= tautB * r2);
      // Wrinkled (r > 0 there); r = 0 lanes are taut or slack and take 1/r = 1 so no lane divides by zero.
      const Vd r = lanes::sqrt(r2);
      const Vd ir = one / lanes::select(r2 > 0.0, r, one);
      const Vd e1 = em + r;
      const Vd s1 = young * e1;
      const Vd c2 = hd * ir, s2 = 0.5 * g12 * ir;
      const Vm keep = taut & ~slack;  // slack is tested first, as in the per-element law
      S0 = lanes::select(slack, zero, lanes::select(keep, S0, 0.5 * s1 * (1.0 + c2)));
      S1 = lanes::select(slack, zero, lanes::select(keep, S1, 0.5 * s1 * (1.0 - c2)));
      S2 = lanes::select(slack, zero, lanes::select(keep, S2, 0.5 * s1 * s2));
      if constexpr (Energy) w = lanes::select(slack, zero, lanes::select(keep, w, 0.5 * s1 * e1));
    }
    if constexpr (Energy) energy += tA0 * w;
    const Vd stiff = lanes::max(one, stiffA * (lanes::max(C11, C22) + lanes::abs(C12)) - stiffB);
    const Vd rs2 = lanes::load(refStep2 + e);
    if constexpr (Viscous) {
      // Smallest current altitude² (2A)²/l_max², the bulk viscosity's length.
      const Vd* da = d21;
      const Vd* db = d31;
      const Vd cx = da[1] * db[2] - da[2] * db[1], cy = da[2] * db[0] - da[0] * db[2],
               cz = da[0] * db[1] - da[1] * db[0];
      const Vd l21 = da[0] * da[0] + da[1] * da[1] + da[2] * da[2];
      const Vd l31 = db[0] * db[0] + db[1] * db[1] + db[2] * db[2];
      const Vd l32 = (db[0] - da[0]) * (db[0] - da[0]) + (db[1] - da[1]) * (db[1] - da[1]) +
                     (db[2] - da[2]) * (db[2] - da[2]);
      const Vd le = lanes::sqrt((cx * cx + cy * cy + cz * cz) / lanes::max(l21, lanes::max(l31, l32)));
      Vd q[3][3];  // nodal velocities, node a, component i
      for (int a = 0; a < 3; ++a) lanes::gather3(v, n[a], q[a]);
      Vd h1[3], h2[3];
      for (int i = 0; i < 3; ++i) {
        h1[i] = (q[1][i] - q[0][i]) * n2x;
        h2[i] = (q[1][i] - q[0][i]) * n2y + (q[2][i] - q[0][i]) * n3y;
      }
      const Vd r11 = f1[0] * h1[0] + f1[1] * h1[1] + f1[2] * h1[2];
      const Vd r22 = f2[0] * h2[0] + f2[1] * h2[1] + f2[2] * h2[2];
      const Vd r12 =
          f1[0] * h2[0] + f1[1] * h2[1] + f1[2] * h2[2] + f2[0] * h1[0] + f2[1] * h1[1] + f2[2] * h1[2];
      const Vd ws = lanes::load(iws + e);
      const Vd bulk = visc.bulkB1 * c11 * ws * le * (r11 + r22);
      S0 += visc.beta * c11 * (r11 + nu * r22) + bulk;
      S1 += visc.beta * c11 * (r22 + nu * r11) + bulk;
      S2 += visc.beta * 0.5 * c11 * (1.0 - nu) * r12;
      const Vd dt0 = lanes::sqrt(rs2 / stiff);
      const Vd xi = visc.beta / dt0 + visc.bulkB1;
      minDt = lanes::min(minDt, dt0 * (lanes::sqrt(1.0 + xi * xi) - xi));
    } else {
      const Vm lower = rs2 * bestDen < bestNum * stiff;
      bestNum = lanes::select(lower, rs2, bestNum);
      bestDen = lanes::select(lower, stiff, bestDen);
    }
    // Nodal forces t A0 F S ∇N_a, scattered lane by lane in element order.
    const Vd a2 = tA0 * n2x, b2 = tA0 * n2y, b3 = tA0 * n3y;
    Vd G1[3], G2[3], G3[3];
    for (int i = 0; i < 3; ++i) {
      const Vd p1 = f1[i] * S0 + f2[i] * S2;
      const Vd p2 = f1[i] * S2 + f2[i] * S1;
      G2[i] = p1 * a2 + p2 * b2;
      G3[i] = p2 * b3;
      G1[i] = -(G2[i] + G3[i]);
    }
    lanes::scatterAdd3(f, n[1], G2);
    lanes::scatterAdd3(f, n[2], G3);
    lanes::scatterAdd3(f, n[0], G1);
  }

  // Fold the lanes into the context in lane order.
  if constexpr (Viscous) {
    for (int l = 0; l < kWidth; ++l) ctx.minStableDt = std::min(ctx.minStableDt, minDt[l]);
  } else {
    double num = num0, den = den0;
    for (int l = 0; l < kWidth; ++l)
      if (bestNum[l] * den < num * bestDen[l]) num = bestNum[l], den = bestDen[l];
    if (den > 0) ctx.minStableDt = std::sqrt(num / den);
  }
  if constexpr (Energy) ctx.strainEnergy += lanes::sum(energy);
  return stop;
}

}  // namespace fsi::structure::membrane
