#include "structure/effects/MembraneForces.hpp"

#include <algorithm>
#include <cmath>

#include "structure/material/WrinklingMembrane.hpp"

namespace fsi::structure {

namespace {

// Current corotational frame and the in-plane deformation gradient of one triangle.
struct Kinematics {
  double e1[3], e2[3];
  double a2, c2, maxEdge2;    // squared edge 1-2, squared height of node 3 over it, longest squared edge
  double F11, F12, F22;       // F = [[F11, F12], [0, F22]]
  double ia0, b0, ic0, tA0;   // reference geometry
};

inline void kinematics(const double* __restrict x, const int* n, const double* __restrict g, Kinematics& k) {
  const double* p1 = x + 3 * n[0];
  const double* p2 = x + 3 * n[1];
  const double* p3 = x + 3 * n[2];
  const double d21[3] = {p2[0] - p1[0], p2[1] - p1[1], p2[2] - p1[2]};
  const double d31[3] = {p3[0] - p1[0], p3[1] - p1[1], p3[2] - p1[2]};
  k.a2 = d21[0] * d21[0] + d21[1] * d21[1] + d21[2] * d21[2];
  const double a = std::sqrt(k.a2);
  const double ia = 1.0 / a;
  for (int i = 0; i < 3; ++i) k.e1[i] = d21[i] * ia;
  const double b = d31[0] * k.e1[0] + d31[1] * k.e1[1] + d31[2] * k.e1[2];
  const double w[3] = {d31[0] - b * k.e1[0], d31[1] - b * k.e1[1], d31[2] - b * k.e1[2]};
  k.c2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
  // A triangle collapsed to a line has no e2; the tiny shift keeps forces finite (F22 -> 0 gives the
  // physically right slack/compressed response) instead of producing 0/0.
  const double c = std::sqrt(k.c2);
  const double ic = 1.0 / (c + 1e-300);
  for (int i = 0; i < 3; ++i) k.e2[i] = w[i] * ic;
  const double l31 = d31[0] * d31[0] + d31[1] * d31[1] + d31[2] * d31[2];
  const double l32 = l31 + k.a2 - 2.0 * (d21[0] * d31[0] + d21[1] * d31[1] + d21[2] * d31[2]);
  k.maxEdge2 = std::max(k.a2, std::max(l31, l32));
  k.ia0 = g[0];
  k.b0 = g[1];
  k.ic0 = g[2];
  k.tA0 = g[3];
  k.F11 = a * k.ia0;
  k.F22 = c * k.ic0;
  k.F12 = (b - k.F11 * k.b0) * k.ic0;
}

template <bool Wrinkling>
inline WrinkleState stress(const Kinematics& k, const MembraneBlock& blk, double S[3], double& w) {
  const double e11 = 0.5 * (k.F11 * k.F11 - 1.0);
  const double e22 = 0.5 * (k.F12 * k.F12 + k.F22 * k.F22 - 1.0);
  const double g12 = k.F11 * k.F12;
  if constexpr (Wrinkling) {
    return wrinklingStress(e11, e22, g12, blk.young, blk.c11, blk.poisson, S, w);
  } else {
    return elasticStress(e11, e22, g12, blk.c11, blk.poisson, S, w);
  }
}

template <bool Wrinkling, bool Viscous, bool Energy>
void membraneBlock(const MembraneTriangles& el, const MembraneBlock& blk, const MembraneViscosity& visc,
                   ForceContext& ctx) {
  const double* __restrict x = ctx.x;
  const double* __restrict v = ctx.v;
  double* __restrict f = ctx.fint;
  const int* conn = el.conn.data();
  const double* geo = el.geo.data();
  const double* iws = el.invWaveSpeed.data();
  double minDt2 = ctx.minStableDt * ctx.minStableDt;
  double minDt = ctx.minStableDt;
  double energy = 0.0;
  for (int e = blk.begin; e < blk.end; ++e) {
    const int* n = conn + 3 * e;
    Kinematics k;
    kinematics(x, n, geo + MembraneTriangles::kGeo * e, k);
    double S[3], w;
    stress<Wrinkling>(k, blk, S, w);
    if constexpr (Energy) energy += k.tA0 * w;

    // Shape-function gradients on the reference triangle (node 1 follows from the sum being zero).
    const double n2x = k.ia0, n2y = -k.b0 * k.ia0 * k.ic0, n3y = k.ic0;
    // Stable step: smallest altitude 2A/l_max over the dilatational wave speed.
    const double le2 = k.a2 * k.c2 / k.maxEdge2;
    if constexpr (Viscous) {
      const double* v1 = v + 3 * n[0];
      const double* v2 = v + 3 * n[1];
      const double* v3 = v + 3 * n[2];
      const double dv2[3] = {v2[0] - v1[0], v2[1] - v1[1], v2[2] - v1[2]};
      const double dv3[3] = {v3[0] - v1[0], v3[1] - v1[1], v3[2] - v1[2]};
      const double u2x = dv2[0] * k.e1[0] + dv2[1] * k.e1[1] + dv2[2] * k.e1[2];
      const double u2y = dv2[0] * k.e2[0] + dv2[1] * k.e2[1] + dv2[2] * k.e2[2];
      const double u3x = dv3[0] * k.e1[0] + dv3[1] * k.e1[1] + dv3[2] * k.e1[2];
      const double u3y = dv3[0] * k.e2[0] + dv3[1] * k.e2[1] + dv3[2] * k.e2[2];
      const double Fd11 = u2x * n2x, Fd12 = u2x * n2y + u3x * n3y;
      const double Fd21 = u2y * n2x, Fd22 = u2y * n2y + u3y * n3y;
      const double r11 = k.F11 * Fd11;
      const double r22 = k.F12 * Fd12 + k.F22 * Fd22;
      const double r12 = k.F11 * Fd12 + k.F12 * Fd11 + k.F22 * Fd21;  // 2 Ė12
      const double le = std::sqrt(le2);
      const double c = 1.0 / iws[e];
      const double bulk = visc.bulkB1 * blk.density * c * le * (r11 + r22);
      S[0] += visc.beta * blk.c11 * (r11 + blk.poisson * r22) + bulk;
      S[1] += visc.beta * blk.c11 * (r22 + blk.poisson * r11) + bulk;
      S[2] += visc.beta * 0.5 * blk.c11 * (1.0 - blk.poisson) * r12;
      // Damped stability limit (L/c)(sqrt(1+ξ²) − ξ) with ξ = βω/2 + b1, ω = 2c/L.
      const double xi = visc.beta * c / le + visc.bulkB1;
      minDt = std::min(minDt, le * iws[e] * (std::sqrt(1.0 + xi * xi) - xi));
    } else {
      minDt2 = std::min(minDt2, le2 * iws[e] * iws[e]);
    }
    // First Piola–Kirchhoff P = F S, nodal forces t A0 P ∇N_a in the current frame.
    const double P11 = k.F11 * S[0] + k.F12 * S[2];
    const double P12 = k.F11 * S[2] + k.F12 * S[1];
    const double P21 = k.F22 * S[2];
    const double P22 = k.F22 * S[1];
    const double f2x = k.tA0 * (P11 * n2x + P12 * n2y);
    const double f2y = k.tA0 * (P21 * n2x + P22 * n2y);
    const double f3x = k.tA0 * P12 * n3y;
    const double f3y = k.tA0 * P22 * n3y;
    double* F1 = f + 3 * n[0];
    double* F2 = f + 3 * n[1];
    double* F3 = f + 3 * n[2];
    for (int i = 0; i < 3; ++i) {
      const double g2 = f2x * k.e1[i] + f2y * k.e2[i];
      const double g3 = f3x * k.e1[i] + f3y * k.e2[i];
      F2[i] += g2;
      F3[i] += g3;
      F1[i] -= g2 + g3;
    }
  }
  if constexpr (Viscous) {
    ctx.minStableDt = minDt;
  } else {
    ctx.minStableDt = std::sqrt(minDt2);
  }
  if constexpr (Energy) ctx.strainEnergy += energy;
}

template <bool Wrinkling, bool Viscous>
void dispatchEnergy(const MembraneTriangles& el, const MembraneBlock& b, const MembraneViscosity& v,
                    ForceContext& ctx) {
  if (ctx.wantEnergy) {
    membraneBlock<Wrinkling, Viscous, true>(el, b, v, ctx);
  } else {
    membraneBlock<Wrinkling, Viscous, false>(el, b, v, ctx);
  }
}

}  // namespace

MembraneForces::MembraneForces(const MembraneTriangles& elements, MembraneViscosity viscosity)
    : el_(elements), visc_(viscosity) {}

void MembraneForces::addForces(ForceContext& ctx) const {
  // One branch per material block and step; none per element.
  for (const MembraneBlock& b : el_.blocks) {
    if (b.wrinkling) {
      visc_.enabled() ? dispatchEnergy<true, true>(el_, b, visc_, ctx)
                      : dispatchEnergy<true, false>(el_, b, visc_, ctx);
    } else {
      visc_.enabled() ? dispatchEnergy<false, true>(el_, b, visc_, ctx)
                      : dispatchEnergy<false, false>(el_, b, visc_, ctx);
    }
  }
}

void MembraneForces::evaluate(const double* x, MembraneStressField& out) const {
  const int ne = el_.count;
  out.cauchy.assign(6 * ne, 0.0);
  out.principal.assign(2 * ne, 0.0);
  out.state.assign(ne, 0.0);
  out.majorStrain.assign(ne, 0.0);
  for (const MembraneBlock& blk : el_.blocks) {
    for (int e = blk.begin; e < blk.end; ++e) {
      Kinematics k;
      kinematics(x, &el_.conn[3 * e], &el_.geo[MembraneTriangles::kGeo * e], k);
      double S[3], w;
      const WrinkleState st = blk.wrinkling ? stress<true>(k, blk, S, w) : stress<false>(k, blk, S, w);
      const double e11 = 0.5 * (k.F11 * k.F11 - 1.0);
      const double e22 = 0.5 * (k.F12 * k.F12 + k.F22 * k.F22 - 1.0);
      const double h12 = 0.5 * k.F11 * k.F12;
      out.majorStrain[e] = 0.5 * (e11 + e22) + std::sqrt(0.25 * (e11 - e22) * (e11 - e22) + h12 * h12);
      out.state[e] = double(static_cast<int>(st));
      // Cauchy stress σ = F S Fᵀ / J in the current frame (J = area ratio; thickness change not modelled).
      const double J = k.F11 * k.F22;
      const double iJ = J > 0 ? 1.0 / J : 0.0;
      const double P11 = k.F11 * S[0] + k.F12 * S[2], P12 = k.F11 * S[2] + k.F12 * S[1];
      const double P22 = k.F22 * S[1];
      const double s11 = (P11 * k.F11 + P12 * k.F12) * iJ;
      const double s12 = (P12 * k.F22) * iJ;
      const double s22 = (P22 * k.F22) * iJ;
      const double m = 0.5 * (s11 + s22);
      const double r = std::sqrt(0.25 * (s11 - s22) * (s11 - s22) + s12 * s12);
      out.principal[2 * e] = m + r;
      out.principal[2 * e + 1] = m - r;
      // σ = s11 e1e1 + s22 e2e2 + s12 (e1e2 + e2e1) in global axes.
      const double* a = k.e1;
      const double* b = k.e2;
      double* c = &out.cauchy[6 * e];
      c[0] = s11 * a[0] * a[0] + s22 * b[0] * b[0] + 2 * s12 * a[0] * b[0];
      c[1] = s11 * a[1] * a[1] + s22 * b[1] * b[1] + 2 * s12 * a[1] * b[1];
      c[2] = s11 * a[2] * a[2] + s22 * b[2] * b[2] + 2 * s12 * a[2] * b[2];
      c[3] = s11 * a[0] * a[1] + s22 * b[0] * b[1] + s12 * (a[0] * b[1] + a[1] * b[0]);
      c[4] = s11 * a[1] * a[2] + s22 * b[1] * b[2] + s12 * (a[1] * b[2] + a[2] * b[1]);
      c[5] = s11 * a[0] * a[2] + s22 * b[0] * b[2] + s12 * (a[0] * b[2] + a[2] * b[0]);
    }
  }
}

}  // namespace fsi::structure
