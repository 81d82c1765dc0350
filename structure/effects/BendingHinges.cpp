#include "structure/effects/BendingHinges.hpp"

#include <algorithm>
#include <cmath>

#include "structure/model/Lanes.hpp"

namespace fsi::structure {

using lanes::kWidth;
using lanes::Vd;
using lanes::Vm;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The hinge's geometry in lanes (hingeAngle's notation): e = x4 − x3, a = x1 − x3, b = x1 − x4,
// c = x2 − x4, d = x2 − x3, the normals n1 = a × b, n2 = c × d, |e|, |n1|², |n2|².
struct HingeLanes {
  Vd e[3], a[3], b[3], c[3], d[3], n1[3], n2[3];
  Vd el, n1s, n2s;
  Vm ok;  ///< a proper hinge (edge and both triangles of non-zero size); elsewhere θ = 0, no gradient
};

inline Vd dot(const Vd* p, const Vd* q) {
  return p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
}
inline void cross(const Vd* p, const Vd* q, Vd* r) {
  r[0] = p[1] * q[2] - p[2] * q[1];
  r[1] = p[2] * q[0] - p[0] * q[2];
  r[2] = p[0] * q[1] - p[1] * q[0];
}

inline HingeLanes hingeLanes(const Vd (&p)[4][3]) {
  HingeLanes g;
  for (int i = 0; i < 3; ++i) {
    g.e[i] = p[3][i] - p[2][i];
    g.a[i] = p[0][i] - p[2][i];
    g.b[i] = p[0][i] - p[3][i];
    g.c[i] = p[1][i] - p[3][i];
    g.d[i] = p[1][i] - p[2][i];
  }
  cross(g.a, g.b, g.n1);
  cross(g.c, g.d, g.n2);
  g.el = lanes::sqrt(dot(g.e, g.e));
  g.n1s = dot(g.n1, g.n1);
  g.n2s = dot(g.n2, g.n2);
  g.ok = (g.el > 0.0) & (g.n1s > 0.0) & (g.n2s > 0.0);
  return g;
}

}  // namespace

void bendingAngles(const BendingHinges& H, const double* x, double* dtheta, int begin, int end) {
  const Vd zero = lanes::splat(0.0);
  for (int h = begin; h < end; h += kWidth) {
    Vd p[4][3];
    for (std::size_t k = 0; k < 4; ++k)
      lanes::gather3(x, &H.nodes[k * std::size_t(H.padded) + std::size_t(h)], p[k]);
    const HingeLanes g = hingeLanes(p);
    Vd m[3];
    cross(g.n2, g.n1, m);
    // atan2(m·e/|e|, n1·n2), both arguments scaled by |e| > 0: the same angle without a division.
    const Vd theta = lanes::select(g.ok, lanes::atan2(dot(m, g.e), dot(g.n1, g.n2) * g.el), zero);
    // θ − θ0 in (−π, π], as FabricBending's wrapAngle.
    const Vd d = theta - lanes::load(&H.theta0[std::size_t(h)]);
    lanes::store(&dtheta[h], lanes::select(d > kPi, d - 2 * kPi, lanes::select(d <= -kPi, d + 2 * kPi, d)));
  }
}

void bendingForces(const BendingHinges& H, const double* mass, const double* dtheta, ForceContext& ctx,
                   int begin, int end) {
  // The arrays through restricted pointers: the force writes cannot alias them (no reloads per batch).
  double* __restrict f = ctx.fint;
  const double* __restrict x = ctx.x;
  const double* __restrict dth = dtheta;
  const int* __restrict nodes = H.nodes.data();
  const int* __restrict neighbour = H.neighbour.data();
  const double* __restrict coef = H.coef.data();
  const double* __restrict selfCoef = H.selfCoef.data();
  const double* __restrict stiffness = H.stiffness.data();
  const std::size_t P = std::size_t(H.padded);
  const bool wantEnergy = ctx.wantEnergy;
  const Vd one = lanes::splat(1.0), zero = lanes::splat(0.0);
  Vd energy = zero, bestNum = zero, bestDen = one;  // the largest ω² = num/den per lane, no division
  for (int h = begin; h < end; h += kWidth) {
    const std::size_t at = std::size_t(h);
    // The moment ∂E/∂θ_h: its row of K times the angles (padded lanes have a zero row).
    const Vd own = lanes::load(&dth[at]);
    Vd moment = lanes::load(&selfCoef[at]) * own;
    for (std::size_t j = 0; j < std::size_t(BendingHinges::kNeighbours); ++j) {
      double t[kWidth];
      for (std::size_t l = 0; l < std::size_t(kWidth); ++l) t[l] = dth[neighbour[j * P + at + l]];
      moment += lanes::load(&coef[j * P + at]) * lanes::load(t);
    }
    if (wantEnergy) energy += 0.5 * own * moment;
    // ∂θ/∂x (hingeAngle): |e| n1/|n1|², |e| n2/|n2|², and the edge's two vertices the rest (zero where the
    // hinge is degenerate).
    Vd p[4][3];
    for (std::size_t k = 0; k < 4; ++k) lanes::gather3(x, &nodes[k * P + at], p[k]);
    const HingeLanes g = hingeLanes(p);
    // One division: w1 = 1/(|e| |n1|²), w2 = 1/(|e| |n2|²) (zero where degenerate); |e|/|n1|² = |e|² w1.
    const Vd el = lanes::select(g.ok, g.el, one), n1s = lanes::select(g.ok, g.n1s, one),
             n2s = lanes::select(g.ok, g.n2s, one);
    const Vd inv = lanes::select(g.ok, one / (el * n1s * n2s), zero);
    const Vd w1 = n2s * inv, w2 = n1s * inv, el2 = el * el;
    const Vd s1 = el2 * w1, s2 = el2 * w2;
    const Vd a3 = dot(g.b, g.e) * w1, b3 = dot(g.c, g.e) * w2;
    const Vd a4 = -dot(g.a, g.e) * w1, b4 = -dot(g.d, g.e) * w2;
    Vd gr[4][3];
    for (int i = 0; i < 3; ++i) {
      gr[0][i] = s1 * g.n1[i];
      gr[1][i] = s2 * g.n2[i];
      gr[2][i] = a3 * g.n1[i] + b3 * g.n2[i];
      gr[3][i] = a4 * g.n1[i] + b4 * g.n2[i];
    }
    const int valid = std::min(kWidth, end - h);
    for (std::size_t v = 0; v < 4; ++v) {
      const Vd fv[3] = {moment * gr[v][0], moment * gr[v][1], moment * gr[v][2]};
      const int* n = &nodes[v * P + at];
      if (valid == kWidth) {
        lanes::scatterAdd3(f, n, fv);
      } else {
        for (int l = 0; l < valid; ++l)
          for (int i = 0; i < 3; ++i) f[3 * n[l] + i] += fv[i][l];
      }
    }
    if (mass != nullptr) {
      Vd gn[4];
      for (int v = 0; v < 4; ++v) gn[v] = lanes::sqrt(dot(gr[v], gr[v]));
      const Vd ks = lanes::load(&stiffness[at]) * (gn[0] + gn[1] + gn[2] + gn[3]);
      for (std::size_t v = 0; v < 4; ++v) {
        double mv[kWidth];
        for (std::size_t l = 0; l < std::size_t(kWidth); ++l) mv[l] = mass[nodes[v * P + at + l]];
        const Vd m = lanes::load(mv), num = ks * gn[v];
        const Vm higher = (m > 0.0) & (num * bestDen > bestNum * m);
        bestNum = lanes::select(higher, num, bestNum);
        bestDen = lanes::select(higher, m, bestDen);
      }
    }
  }
  if (wantEnergy) ctx.strainEnergy += lanes::sum(energy);
  double w2max = 0;
  for (int l = 0; l < kWidth; ++l) w2max = std::max(w2max, bestNum[l] / bestDen[l]);
  if (w2max > 0) ctx.minStableDt = std::min(ctx.minStableDt, 2.0 / std::sqrt(w2max));
}

}  // namespace fsi::structure
