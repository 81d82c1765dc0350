#include "structure/elements/MembraneForces.hpp"

#include <algorithm>
#include <cmath>

#include "structure/elements/MembraneBatch.hpp"
#include "structure/elements/MembraneKinematics.hpp"

namespace fsi::structure {

namespace {

using membrane::Kinematics;
using membrane::kinematics;
using membrane::stress;

// Squared smallest altitude (2A)²/l_max² of the current triangle (the bulk viscosity's element length), as
// numerator and denominator.
inline void altitude2(const Kinematics& k, double& num, double& den) {
  const double* a = k.d21;
  const double* b = k.d31;
  const double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2], cz = a[0] * b[1] - a[1] * b[0];
  const double l21 = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
  const double l31 = b[0] * b[0] + b[1] * b[1] + b[2] * b[2];
  const double l32 =
      (b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + (b[2] - a[2]) * (b[2] - a[2]);
  num = cx * cx + cy * cy + cz * cz;
  den = std::max(l21, std::max(l31, l32));
}

// Stiffening of the stretched element relative to the reference one, for the stable step. In reference
// coordinates the tangent of the first Piola stress P = F S is bounded by c11 λ1² (material part, λ1² the
// largest eigenvalue of C) plus S1 (geometric part, the largest principal stress), so the wave speed grows
// by sqrt(λ1² + S1/c11): (3λ²−1)/2 under the square root for a bar, 1.15 at 10 % stretch. S1/c11 is at most
// (1+ν) E1 = (1+ν)(λ1²−1)/2 (taut: S1 = c11 (E1 + ν E2), E2 ≤ E1; wrinkled: S1 = Y E1, Y ≤ c11), so the
// factor follows from C alone, off the stress's critical path; a Gershgorin bound stands in for λ1² (no
// square root; exact for principal axes along the frame and for pure shear). Never below 1: the reference
// step stays the bound for compressed or slack elements.
inline double stiffening(const Kinematics& k, double a, double b) {
  const double c1 = std::max(k.C11, k.C22) + std::abs(k.C12);
  return std::max(1.0, a * c1 - b);
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
  const double* refStep2 = el.refStep2.data();
  const double stiffA = 1.0 + 0.5 * (1.0 + blk.poisson), stiffB = 0.5 * (1.0 + blk.poisson);
  // Running minimum of Δt² = num/den kept as a fraction; one division per block instead of per element.
  double bestNum = ctx.minStableDt * ctx.minStableDt, bestDen = 1.0;
  if (!std::isfinite(bestNum)) bestNum = 1.0, bestDen = 0.0;
  double minDt = ctx.minStableDt;
  double energy = 0.0;
  for (int e = blk.begin; e < blk.end; ++e) {
    const int* n = conn + 3 * e;
    Kinematics k;
    kinematics(x, n, geo + MembraneTriangles::kGeo * e, k);
    double S[3], w;
    stress<Wrinkling>(k, blk, S, w);
    if constexpr (Energy) energy += k.tA0 * w;
    // Stable step from the reference one and the current stiffening (the current altitude grows with the
    // stretch while the step must shrink).
    const double stiff = stiffening(k, stiffA, stiffB);
    if constexpr (Viscous) {
      double aNum, aDen;
      altitude2(k, aNum, aDen);
      const double le2 = aNum / aDen;  // current size: the bulk viscosity's length
      // Ė = sym(FᵀḞ) with Ḟ built like F from the nodal velocity differences.
      const double* v1 = v + 3 * n[0];
      const double* v2 = v + 3 * n[1];
      const double* v3 = v + 3 * n[2];
      double g1[3], g2[3];
      for (int i = 0; i < 3; ++i) {
        g1[i] = (v2[i] - v1[i]) * k.n2x;
        g2[i] = (v2[i] - v1[i]) * k.n2y + (v3[i] - v1[i]) * k.n3y;
      }
      const double r11 = k.f1[0] * g1[0] + k.f1[1] * g1[1] + k.f1[2] * g1[2];
      const double r22 = k.f2[0] * g2[0] + k.f2[1] * g2[1] + k.f2[2] * g2[2];
      const double r12 = k.f1[0] * g2[0] + k.f1[1] * g2[1] + k.f1[2] * g2[2] + k.f2[0] * g1[0] +
                         k.f2[1] * g1[1] + k.f2[2] * g1[2];  // 2 Ė12
      // Bulk viscosity b1 ρ c L_e tr(Ė) with the element's own ρ and c: mass scaling raises ρ by s and lowers
      // c by √s, and c_d² = c11/ρ gives ρ c = c11/c = c11 · invWaveSpeed, scaled or not. With the unscaled
      // density a scaled element would get the damping ratio b1/s instead of the b1 the damped step below
      // assumes.
      const double le = std::sqrt(le2);
      const double bulk = visc.bulkB1 * blk.c11 * iws[e] * le * (r11 + r22);
      S[0] += visc.beta * blk.c11 * (r11 + blk.poisson * r22) + bulk;
      S[1] += visc.beta * blk.c11 * (r22 + blk.poisson * r11) + bulk;
      S[2] += visc.beta * 0.5 * blk.c11 * (1.0 - blk.poisson) * r12;
      // Damped stability limit (L/c)(sqrt(1+ξ²) − ξ) with ξ = βω/2 + b1, ω = 2c/L, L/c = h0/(c
      // sqrt(stiffening)).
      const double dt0 = std::sqrt(refStep2[e] / stiff);
      const double xi = visc.beta / dt0 + visc.bulkB1;
      minDt = std::min(minDt, dt0 * (std::sqrt(1.0 + xi * xi) - xi));
    } else {
      if (refStep2[e] * bestDen < bestNum * stiff) bestNum = refStep2[e], bestDen = stiff;
    }
    // Nodal forces t A0 F S ∇N_a: P = F S has columns p1 = f1 S11 + f2 S12, p2 = f1 S12 + f2 S22.
    double* F1 = f + 3 * n[0];
    double* F2 = f + 3 * n[1];
    double* F3 = f + 3 * n[2];
    const double a2 = k.tA0 * k.n2x, b2 = k.tA0 * k.n2y, b3 = k.tA0 * k.n3y;
    for (int i = 0; i < 3; ++i) {
      const double p1 = k.f1[i] * S[0] + k.f2[i] * S[2];
      const double p2 = k.f1[i] * S[2] + k.f2[i] * S[1];
      const double g2 = p1 * a2 + p2 * b2;
      const double g3 = p2 * b3;
      F2[i] += g2;
      F3[i] += g3;
      F1[i] -= g2 + g3;
    }
  }
  if constexpr (Viscous) {
    ctx.minStableDt = minDt;
  } else {
    ctx.minStableDt = bestDen > 0 ? std::sqrt(bestNum / bestDen) : ctx.minStableDt;
  }
  if constexpr (Energy) ctx.strainEnergy += energy;
}

// The batched kernel over the block's whole batches, the per-element one over the remainder.
template <bool Wrinkling, bool Viscous, bool Energy>
void batchedBlock(const MembraneTriangles& el, const MembraneBlock& blk, const MembraneViscosity& visc,
                  ForceContext& ctx) {
  MembraneBlock rest = blk;
  rest.begin = membrane::membraneBatches<Wrinkling, Viscous, Energy>(el, blk, visc, ctx);
  if (rest.begin < rest.end) membraneBlock<Wrinkling, Viscous, Energy>(el, rest, visc, ctx);
}

template <bool Wrinkling, bool Viscous>
void dispatchEnergy(const MembraneTriangles& el, const MembraneBlock& b, const MembraneViscosity& v,
                    MembraneKernel kernel, ForceContext& ctx) {
  if (kernel == MembraneKernel::Batched) {
    ctx.wantEnergy ? batchedBlock<Wrinkling, Viscous, true>(el, b, v, ctx)
                   : batchedBlock<Wrinkling, Viscous, false>(el, b, v, ctx);
  } else {
    ctx.wantEnergy ? membraneBlock<Wrinkling, Viscous, true>(el, b, v, ctx)
                   : membraneBlock<Wrinkling, Viscous, false>(el, b, v, ctx);
  }
}

// Elements [begin, end) on the calling thread, block by block (one branch per block and step, none per
// element).
void evaluateRange(const MembraneTriangles& el, const MembraneViscosity& visc, MembraneKernel kernel,
                   int begin, int end, ForceContext& ctx) {
  for (const MembraneBlock& b : el.blocks) {
    MembraneBlock part = b;
    part.begin = std::max(b.begin, begin);
    part.end = std::min(b.end, end);
    if (part.begin >= part.end) continue;
    if (part.wrinkling) {
      visc.enabled() ? dispatchEnergy<true, true>(el, part, visc, kernel, ctx)
                     : dispatchEnergy<true, false>(el, part, visc, kernel, ctx);
    } else {
      visc.enabled() ? dispatchEnergy<false, true>(el, part, visc, kernel, ctx)
                     : dispatchEnergy<false, false>(el, part, visc, kernel, ctx);
    }
  }
}

}  // namespace

MembraneForces::MembraneForces(const MembraneTriangles& elements, MembraneViscosity viscosity,
                               MembraneKernel kernel)
    : el_(elements), visc_(viscosity), kernel_(kernel) {}

void MembraneForces::addForces(ForceContext& ctx) const {
  evaluateRange(el_, visc_, kernel_, 0, el_.count, ctx);
}

void MembraneForces::addRange(ForceContext& ctx, int begin, int end) const {
  evaluateRange(el_, visc_, kernel_, begin, end, ctx);
}

Connectivity MembraneForces::connectivity() const {
  Connectivity c;
  c.items = el_.count;
  c.nodesPerItem = 3;
  c.nodes = el_.conn.data();
  c.batch = kernel_ == MembraneKernel::Batched ? membrane::kWidth : 1;
  return c;
}

void MembraneForces::evaluate(const double* x, MembraneStressField& out) const {
  membraneStresses(el_, x, out);
}

void membraneStresses(const MembraneTriangles& el, const double* x, MembraneStressField& out) {
  const int ne = el.count;
  out.cauchy.assign(6 * ne, 0.0);
  out.principal.assign(2 * ne, 0.0);
  out.state.assign(ne, 0.0);
  out.majorStrain.assign(ne, 0.0);
  for (const MembraneBlock& blk : el.blocks) {
    for (int e = blk.begin; e < blk.end; ++e) {
      Kinematics k;
      kinematics(x, &el.conn[3 * e], &el.geo[MembraneTriangles::kGeo * e], k);
      double S[3], w;
      const WrinkleState st = blk.wrinkling ? stress<true>(k, blk, S, w) : stress<false>(k, blk, S, w);
      double e11, e22, g12;
      membrane::greenStrain(k, e11, e22, g12);
      const double h12 = 0.5 * g12;
      out.majorStrain[e] = 0.5 * (e11 + e22) + std::sqrt(0.25 * (e11 - e22) * (e11 - e22) + h12 * h12);
      out.state[e] = double(static_cast<int>(st));
      // Cauchy stress σ = F S Fᵀ / J (J = current/reference area; thickness change not modelled).
      const double J = std::sqrt(std::max(0.0, k.C11 * k.C22 - k.C12 * k.C12));
      const double iJ = J > 0 ? 1.0 / J : 0.0;
      double p1[3], p2[3];
      for (int i = 0; i < 3; ++i) {
        p1[i] = k.f1[i] * S[0] + k.f2[i] * S[2];
        p2[i] = k.f1[i] * S[2] + k.f2[i] * S[1];
      }
      auto sig = [&](int i, int j) { return (p1[i] * k.f1[j] + p2[i] * k.f2[j]) * iJ; };
      double* c = &out.cauchy[6 * e];
      c[0] = sig(0, 0);
      c[1] = sig(1, 1);
      c[2] = sig(2, 2);
      c[3] = sig(0, 1);
      c[4] = sig(1, 2);
      c[5] = sig(0, 2);
      // In-plane principal values: the eigenvalues of S C / J (same spectrum as F S Fᵀ / J on the plane).
      const double t = (S[0] * k.C11 + 2.0 * S[2] * k.C12 + S[1] * k.C22) * iJ;
      const double d = (S[0] * S[1] - S[2] * S[2]) * (k.C11 * k.C22 - k.C12 * k.C12) * iJ * iJ;
      const double r = std::sqrt(std::max(0.0, 0.25 * t * t - d));
      out.principal[2 * e] = 0.5 * t + r;
      out.principal[2 * e + 1] = 0.5 * t - r;
    }
  }
}

}  // namespace fsi::structure
