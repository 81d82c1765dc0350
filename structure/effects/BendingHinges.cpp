#include "structure/effects/BendingHinges.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "structure/model/Lanes.hpp"

namespace fsi::structure {

using lanes::kWidth;
using lanes::Vd;
using lanes::Vm;

namespace {

constexpr double kPi = 3.14159265358979323846;
// How far ahead (hinges, triangles) each loop asks for the node data of its first lane: at 10⁵ triangles the
// nodes' coordinates, masses and forces and the angles no longer fit the core's L2 cache, and the loops wait
// on those indirect loads (a prefetch of one lane a batch: −30 % of the bending's time on this machine).
constexpr std::size_t kAhead = 128;

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

inline double laneMax(Vd a) {
  double m = a[0];
  for (int l = 1; l < kWidth; ++l) m = std::max(m, a[l]);
  return m;
}

// The working memory: Δθ (padded), the scaled moments (padded; 1/|e| after the angles pass), a step bound
// and an energy per batch.
struct Scratch {
  double* dtheta;
  double* moment;
  double* bound;
  double* energy;
};
inline Scratch scratchOf(const BendingHinges& H, double* s) {
  const std::size_t P = std::size_t(H.padded), B = P / std::size_t(kWidth);
  return {s, s + P, s + 2 * P, s + 2 * P + B};
}

// The largest ω² = k_h |g_v| Σ_j |g_j| / m_v over the hinge's four nodes v of positive mass: the gradient as
// hingeAngle's, from one division per batch; the largest ratio by cross-multiplied comparisons, then one
// division.
inline Vd stepBound(const HingeLanes& g, const Vd (&mass)[4], Vd stiffness) {
  const Vd one = lanes::splat(1.0), zero = lanes::splat(0.0);
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
  Vd gn[4], gm[4], mm[4];
  for (int v = 0; v < 4; ++v) {
    gn[v] = lanes::sqrt(dot(gr[v], gr[v]));
    const Vm positive = mass[v] > 0.0;
    gm[v] = lanes::select(positive, gn[v], zero);
    mm[v] = lanes::select(positive, mass[v], one);
  }
  const Vd ks = stiffness * (gn[0] + gn[1] + gn[2] + gn[3]);
  const Vm u = gm[1] * mm[0] > gm[0] * mm[1], w = gm[3] * mm[2] > gm[2] * mm[3];
  const Vd gu = lanes::select(u, gm[1], gm[0]), mu = lanes::select(u, mm[1], mm[0]);
  const Vd gw = lanes::select(w, gm[3], gm[2]), mw = lanes::select(w, mm[3], mm[2]);
  const Vm last = gw * mu > gu * mw;
  return ks * lanes::select(last, gw, gu) / lanes::select(last, mw, mu);
}

}  // namespace

std::size_t BendingHinges::scratch() const {
  return 2 * std::size_t(padded) + 2 * std::size_t(padded / kWidth);
}

void bendingAngles(const BendingHinges& H, const double* mass, const double* x, double* scratch, int begin,
                   int end) {
  const Scratch s = scratchOf(H, scratch);
  const std::size_t P = std::size_t(H.padded);
  const Vd zero = lanes::splat(0.0), one = lanes::splat(1.0);
  for (int h = begin; h < end; h += kWidth) {
    const std::size_t at = std::size_t(h);
    Vd p[4][3];
    for (std::size_t k = 0; k < 4; ++k) lanes::gather3(x, &H.nodes[k * P + at], p[k]);
    if (at + kAhead < P)
      for (std::size_t k = 0; k < 4; ++k) {
        __builtin_prefetch(&x[3 * H.nodes[k * P + at + kAhead]]);
        if (mass != nullptr) __builtin_prefetch(&mass[H.nodes[k * P + at + kAhead]]);
      }
    const HingeLanes g = hingeLanes(p);
    Vd m[3];
    cross(g.n2, g.n1, m);
    // atan2(m·e/|e|, n1·n2), both arguments scaled by |e| > 0: the same angle without a division.
    const Vd theta = lanes::select(g.ok, lanes::atan2(dot(m, g.e), dot(g.n1, g.n2) * g.el), zero);
    // θ − θ0 in (−π, π], as FabricBending's wrapAngle.
    const Vd d = theta - lanes::load(&H.theta0[at]);
    lanes::store(&s.dtheta[at],
                 lanes::select(d > kPi, d - 2 * kPi, lanes::select(d <= -kPi, d + 2 * kPi, d)));
    lanes::store(&s.moment[at], lanes::select(g.ok, one / lanes::select(g.ok, g.el, one), zero));
    double w2 = 0;
    if (mass != nullptr) {
      Vd mv[4];
      for (std::size_t v = 0; v < 4; ++v) {
        double t[kWidth];
        for (std::size_t l = 0; l < std::size_t(kWidth); ++l) t[l] = mass[H.nodes[v * P + at + l]];
        mv[v] = lanes::load(t);
      }
      w2 = laneMax(stepBound(g, mv, lanes::load(&H.stiffness[at])));
    }
    s.bound[at / kWidth] = w2;
  }
}

void bendingMoments(const BendingHinges& H, double* scratch, bool wantEnergy, int begin, int end) {
  const Scratch s = scratchOf(H, scratch);
  const double* __restrict dth = s.dtheta;
  double* __restrict q = s.moment;
  const int* __restrict neighbour = H.neighbour.data();
  const double* __restrict coef = H.coef.data();
  const std::size_t P = std::size_t(H.padded);
  for (int h = begin; h < end; h += kWidth) {
    const std::size_t at = std::size_t(h);
    // The moment ∂E/∂θ_h: its row of K times the angles (padded lanes have a zero row).
    const Vd own = lanes::load(&dth[at]);
    Vd moment = lanes::load(&H.selfCoef[at]) * own;
    if (at + kAhead < P)
      for (std::size_t j = 0; j < std::size_t(BendingHinges::kNeighbours); ++j)
        __builtin_prefetch(&dth[neighbour[j * P + at + kAhead]]);
    for (std::size_t j = 0; j < std::size_t(BendingHinges::kNeighbours); ++j) {
      double t[kWidth];
      for (std::size_t l = 0; l < std::size_t(kWidth); ++l) t[l] = dth[neighbour[j * P + at + l]];
      moment += lanes::load(&coef[j * P + at]) * lanes::load(t);
    }
    if (wantEnergy) s.energy[at / kWidth] = lanes::sum(0.5 * own * moment);
    lanes::store(&q[at], moment * lanes::load(&q[at]));
  }
  // The padded lane the triangles name for an edge without a hinge: no moment (also when it lies in a batch
  // past the last range).
  if (end >= H.count) q[H.count] = 0.0;
}

void bendingForces(const BendingHinges& H, const double* scratch, ForceContext& ctx, int begin, int end) {
  const std::size_t P = std::size_t(H.padded);
  const double* bound = scratch + 2 * P;
  const double* energy = bound + P / std::size_t(kWidth);
  const int b0 = begin / kWidth, b1 = (end + kWidth - 1) / kWidth;
  double w2max = 0;
  for (int b = b0; b < b1; ++b) w2max = std::max(w2max, bound[b]);
  if (w2max > 0) ctx.minStableDt = std::min(ctx.minStableDt, 2.0 / std::sqrt(w2max));
  if (ctx.wantEnergy) {
    double e = 0;
    for (int b = b0; b < b1; ++b) e += energy[b];
    ctx.strainEnergy += e;
  }

  double* __restrict f = ctx.fint;
  const double* __restrict x = ctx.x;
  const double* __restrict q = scratch + P;
  const int* __restrict tn = H.triNodes.data();
  const int* __restrict th = H.triHinge.data();
  const std::size_t T = std::size_t(H.triPadded);
  const Vd zero = lanes::splat(0.0), one = lanes::splat(1.0);
  const int first = H.batchFirstTriangle[std::size_t(b0)], last = H.batchFirstTriangle[std::size_t(b1)];
  for (int t = first; t < last; t += kWidth) {
    const std::size_t at = std::size_t(t);
    Vd p[3][3];
    for (std::size_t k = 0; k < 3; ++k) lanes::gather3(x, &tn[k * T + at], p[k]);
    if (at + kAhead < T)
      for (std::size_t k = 0; k < 3; ++k) {
        const int v = th[k * T + at + kAhead];
        __builtin_prefetch(&x[3 * tn[k * T + at + kAhead]]);
        __builtin_prefetch(&f[3 * tn[k * T + at + kAhead]], 1);
        __builtin_prefetch(&q[v ^ (v >> 31)]);
      }
    // Edges E_k = v_{k+1} − v_k, the normal n = (v1 − v0) × (v2 − v0) = E2 × E0.
    Vd E[3][3];
    for (int i = 0; i < 3; ++i) {
      E[0][i] = p[1][i] - p[0][i];
      E[1][i] = p[2][i] - p[1][i];
      E[2][i] = p[0][i] - p[2][i];
    }
    Vd n[3];
    cross(E[2], E[0], n);
    const Vd nn = dot(n, n);
    const Vd inv = lanes::select(nn > 0.0, one / lanes::select(nn > 0.0, nn, one), zero);
    // Edge k: a = v_k, b = v_{k+1}, o = v_{k+2}; L_k = |E_k|², D_k = (o − b)·E_k = E_{k+1}·E_k.
    const Vd L0 = dot(E[0], E[0]), L1 = dot(E[1], E[1]), L2 = dot(E[2], E[2]);
    const Vd D0 = dot(E[1], E[0]), D1 = dot(E[2], E[1]), D2 = dot(E[0], E[2]);
    // The hinges' scaled moments, negated where the hinge is stored as ~h (its gradient on this side against
    // the triangle's normal): the sign bit flipped.
    Vd c[3];
    for (std::size_t k = 0; k < 3; ++k) {
      std::uint64_t m[kWidth];
      for (std::size_t l = 0; l < std::size_t(kWidth); ++l) {
        const int v = th[k * T + at + l];
        std::uint64_t bits;
        std::memcpy(&bits, &q[v ^ (v >> 31)], sizeof bits);
        m[l] = bits ^ (std::uint64_t(std::int64_t(v >> 31)) << 63);
      }
      Vd mv;
      std::memcpy(&mv, m, sizeof mv);
      c[k] = mv * inv;
    }
    // Each vertex: opposite to one edge (|E|²), first end of the next (D), second end of the previous
    // (−D − |E|²).
    const Vd t0 = c[1] * L1 + c[0] * D0 - c[2] * (D2 + L2);
    const Vd t1 = c[2] * L2 + c[1] * D1 - c[0] * (D0 + L0);
    const Vd t2 = c[0] * L0 + c[2] * D2 - c[1] * (D1 + L1);
    const Vd tv[3] = {t0, t1, t2};
    const int valid = std::min(kWidth, last - t);
    for (std::size_t v = 0; v < 3; ++v) {
      const Vd fv[3] = {tv[v] * n[0], tv[v] * n[1], tv[v] * n[2]};
      const int* nv = &tn[v * T + at];
      if (valid == kWidth) {
        lanes::scatterAdd3(f, nv, fv);
      } else {
        for (int l = 0; l < valid; ++l)
          for (int i = 0; i < 3; ++i) f[3 * nv[l] + i] += fv[i][l];
      }
    }
  }
}

}  // namespace fsi::structure
