#include "structure/effects/FabricBending.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

#include "structure/model/Lanes.hpp"

namespace fsi::structure {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kLaneWidth = lanes::kWidth;

inline void sub(const double* a, const double* b, double* r) {
  r[0] = a[0] - b[0];
  r[1] = a[1] - b[1];
  r[2] = a[2] - b[2];
}
inline void cross(const double* a, const double* b, double* r) {
  r[0] = a[1] * b[2] - a[2] * b[1];
  r[1] = a[2] * b[0] - a[0] * b[2];
  r[2] = a[0] * b[1] - a[1] * b[0];
}
inline double dot(const double* a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// θ − θ0 in (−π, π]: a hinge folded through the flat-back position stays a small change, not 2π.
inline double wrapAngle(double d) {
  if (d > kPi) return d - 2 * kPi;
  if (d <= -kPi) return d + 2 * kPi;
  return d;
}

}  // namespace

double hingeAngle(const double* x1, const double* x2, const double* x3, const double* x4, double* g) {
  double e[3], a[3], b[3], c[3], d[3], n1[3], n2[3];
  sub(x4, x3, e);
  sub(x1, x3, a);
  sub(x1, x4, b);
  sub(x2, x4, c);
  sub(x2, x3, d);
  cross(a, b, n1);  // normal of (x1, x3, x4)
  cross(c, d, n2);  // normal of (x2, x4, x3): the same way as n1 when the hinge is flat
  const double el = std::sqrt(dot(e, e)), n1s = dot(n1, n1), n2s = dot(n2, n2);
  if (!(el > 0) || !(n1s > 0) || !(n2s > 0)) {
    if (g != nullptr) std::fill(g, g + 12, 0.0);
    return 0.0;
  }
  double m[3];
  cross(n2, n1, m);
  const double theta = std::atan2(dot(m, e) / el, dot(n1, n2));
  if (g != nullptr) {
    // ∂θ/∂x1 = |e| n1/|n1|², ∂θ/∂x2 = |e| n2/|n2|², and the edge's two vertices take the rest so that the
    // four sum to zero (a translation does not turn the hinge) and have no moment (nor does a rotation).
    const double s1 = el / n1s, s2 = el / n2s;
    const double a3 = dot(b, e) / el / n1s, b3 = dot(c, e) / el / n2s;  // (x1−x4)·e, (x2−x4)·e
    const double a4 = -dot(a, e) / el / n1s, b4 = -dot(d, e) / el / n2s;
    for (int k = 0; k < 3; ++k) {
      g[k] = s1 * n1[k];
      g[3 + k] = s2 * n2[k];
      g[6 + k] = a3 * n1[k] + b3 * n2[k];
      g[9 + k] = a4 * n1[k] + b4 * n2[k];
    }
  }
  return theta;
}

namespace {

using V2 = std::array<double, 2>;

// The slope jump across an edge under a uniform curvature E (one of the three unit symmetric 2×2 matrices),
// for the linear interpolant of z = ½ xᵀ E x over a triangle with 2D vertices q (any orientation): its
// gradient is E c + ½ Σ_i (q_i − c)ᵀ E (q_i − c) ∇λ_i, c the centroid.
V2 interpolantSlope(const std::array<V2, 3>& q, int k) {
  const V2 c{(q[0][0] + q[1][0] + q[2][0]) / 3, (q[0][1] + q[1][1] + q[2][1]) / 3};
  auto quad = [k](const V2& v) {
    return k == 0 ? 0.5 * v[0] * v[0] : k == 1 ? v[0] * v[1] : 0.5 * v[1] * v[1];  // ½ vᵀ E_k v
  };
  auto apply = [k](const V2& v) -> V2 {  // E_k v
    return k == 0 ? V2{v[0], 0} : k == 1 ? V2{v[1], v[0]} : V2{0, v[1]};
  };
  const double area2 = (q[1][0] - q[0][0]) * (q[2][1] - q[0][1]) - (q[1][1] - q[0][1]) * (q[2][0] - q[0][0]);
  V2 g = apply(c);
  for (int i = 0; i < 3; ++i) {
    const V2& a = q[std::size_t((i + 1) % 3)];
    const V2& b = q[std::size_t((i + 2) % 3)];
    const V2 gradLambda{-(b[1] - a[1]) / area2, (b[0] - a[0]) / area2};
    const double w = quad(V2{q[std::size_t(i)][0] - c[0], q[std::size_t(i)][1] - c[1]});
    g[0] += w * gradLambda[0];
    g[1] += w * gradLambda[1];
  }
  return g;
}

bool invert3(const std::array<double, 9>& a, std::array<double, 9>& inv) {
  const double det = a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6]) +
                     a[2] * (a[3] * a[7] - a[4] * a[6]);
  double scale = 0;
  for (double v : a) scale = std::max(scale, std::abs(v));
  if (!(std::abs(det) > 1e-12 * scale * scale * scale)) return false;
  inv = {(a[4] * a[8] - a[5] * a[7]) / det, (a[2] * a[7] - a[1] * a[8]) / det,
         (a[1] * a[5] - a[2] * a[4]) / det, (a[5] * a[6] - a[3] * a[8]) / det,
         (a[0] * a[8] - a[2] * a[6]) / det, (a[2] * a[3] - a[0] * a[5]) / det,
         (a[3] * a[7] - a[4] * a[6]) / det, (a[1] * a[6] - a[0] * a[7]) / det,
         (a[0] * a[4] - a[1] * a[3]) / det};
  return true;
}

}  // namespace

InteriorHinges interiorHinges(const std::vector<int>& conn) {
  std::map<std::pair<int, int>, std::vector<int>> edges;  // (lower node, higher node) -> third vertices
  for (std::size_t t = 0; 3 * t + 2 < conn.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = conn[3 * t + std::size_t(k)], b = conn[3 * t + std::size_t((k + 1) % 3)];
      edges[{std::min(a, b), std::max(a, b)}].push_back(conn[3 * t + std::size_t((k + 2) % 3)]);
    }
  InteriorHinges h;
  for (const auto& [edge, third] : edges) {
    if (third.size() > 2) ++h.seams;
    if (third.size() == 2) h.nodes.insert(h.nodes.end(), {third[0], third[1], edge.first, edge.second});
  }
  return h;
}

FabricBending::FabricBending(std::string label, const std::vector<int>& conn, const std::vector<double>& X,
                             const std::vector<double>* mass, double rigidity)
    : label_(std::move(label)), mass_(mass) {
  const std::size_t nt = conn.size() / 3;
  auto P = [&](int node) { return &X[3 * std::size_t(node)]; };
  const InteriorHinges hinges = interiorHinges(conn);
  hingeNodes_ = hinges.nodes;
  seams_ = hinges.seams;
  std::map<std::pair<int, int>, int> hingeOf;  // edge (lower node, higher node) -> its hinge
  for (std::size_t h = 0; 4 * h < hingeNodes_.size(); ++h) {
    const int* n = &hingeNodes_[4 * h];
    hingeOf[{n[2], n[3]}] = int(h);
    theta0_.push_back(hingeAngle(P(n[0]), P(n[1]), P(n[2]), P(n[3]), nullptr));
  }
  hingeStiffness_.assign(theta0_.size(), 0.0);

  tris_.resize(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const int* v = &conn[3 * t];
    double u[3], w[3], n[3];
    sub(P(v[1]), P(v[0]), u);
    sub(P(v[2]), P(v[0]), w);
    cross(u, w, n);
    const double n2 = std::sqrt(dot(n, n)), ul = std::sqrt(dot(u, u));
    if (!(n2 > 0) || !(ul > 0)) continue;  // degenerate: no curvature (the model refuses such triangles)
    double e1[3], e2[3], nh[3], c[3];
    for (int k = 0; k < 3; ++k) {
      e1[k] = u[k] / ul;
      nh[k] = n[k] / n2;
      c[k] = (P(v[0])[k] + P(v[1])[k] + P(v[2])[k]) / 3;
    }
    cross(nh, e1, e2);
    auto local = [&](const double* p) {
      double d[3];
      sub(p, c, d);
      return V2{dot(d, e1), dot(d, e2)};
    };
    const std::array<V2, 3> q{local(P(v[0])), local(P(v[1])), local(P(v[2]))};
    Triangle& T = tris_[t];
    std::array<double, 9> A{};
    for (int e = 0; e < 3; ++e) {
      const int a = v[e], b = v[(e + 1) % 3], opp = v[(e + 2) % 3];
      const V2 qa = q[std::size_t(e)], qb = q[std::size_t((e + 1) % 3)], qo = q[std::size_t((e + 2) % 3)];
      const double el = std::hypot(qb[0] - qa[0], qb[1] - qa[1]);
      const V2 along{(qb[0] - qa[0]) / el, (qb[1] - qa[1]) / el};
      V2 out{along[1], -along[0]};  // in-plane normal of the edge, pointing away from the opposite vertex
      if (out[0] * (qo[0] - qa[0]) + out[1] * (qo[1] - qa[1]) > 0) out = {-out[0], -out[1]};
      const auto it = hingeOf.find({std::min(a, b), std::max(a, b)});
      if (it == hingeOf.end()) {
        // A free edge (or a seam): no curvature across it.
        for (int k = 0; k < 3; ++k) {
          const double s = k == 1 ? 2 * out[0] * out[1] : (k == 0 ? out[0] * out[0] : out[1] * out[1]);
          A[std::size_t(3 * e + k)] = s;
        }
        continue;
      }
      const int h = it->second;
      const int r = hingeNodes_[4 * std::size_t(h)] == opp ? hingeNodes_[4 * std::size_t(h) + 1]
                                                           : hingeNodes_[4 * std::size_t(h)];
      // The neighbour unfolded about the edge into this triangle's plane.
      double ar[3], eb[3];
      sub(P(r), P(a), ar);
      sub(P(b), P(a), eb);
      const double ebl = std::sqrt(dot(eb, eb));
      const double s = dot(ar, eb) / ebl;
      double perp[3];
      for (int k = 0; k < 3; ++k) perp[k] = ar[k] - s * eb[k] / ebl;
      const double d = std::sqrt(dot(perp, perp));
      const std::array<V2, 3> qn{qa, qb,
                                 V2{qa[0] + s * along[0] + d * out[0], qa[1] + s * along[1] + d * out[1]}};
      for (int k = 0; k < 3; ++k) {
        const V2 gT = interpolantSlope(q, k), gN = interpolantSlope(qn, k);
        A[std::size_t(3 * e + k)] = out[0] * (gN[0] - gT[0]) + out[1] * (gN[1] - gT[1]);
      }
      T.hinge[std::size_t(e)] = h;
      // The hinge's θ is positive for a bowl open towards n1 of its first opposite vertex's triangle.
      const int* hn = &hingeNodes_[4 * std::size_t(h)];
      double m1[3], m2[3], nref[3];
      sub(P(hn[0]), P(hn[2]), m1);
      sub(P(hn[0]), P(hn[3]), m2);
      cross(m1, m2, nref);
      if (hn[0] != opp) {  // this triangle holds the second opposite vertex: compare with n2
        sub(P(hn[1]), P(hn[3]), m1);
        sub(P(hn[1]), P(hn[2]), m2);
        cross(m1, m2, nref);
      }
      T.sign[std::size_t(e)] = dot(nref, nh) >= 0 ? 1.0 : -1.0;
    }
    // A maps (s11, s12, s22) to the three edges' angles: rows are edges. B = A⁻¹ maps angles to S.
    std::array<double, 9> Ainv{};
    if (!invert3(A, Ainv)) {
      T.hinge = {-1, -1, -1};
      continue;
    }
    T.B = Ainv;
    T.weight = rigidity * 0.5 * n2;
    for (int e = 0; e < 3; ++e) {
      if (T.hinge[std::size_t(e)] < 0) continue;
      double k = 0;
      for (int r = 0; r < 3; ++r)
        k += (r == 1 ? 2.0 : 1.0) * T.B[std::size_t(3 * r + e)] * T.B[std::size_t(3 * r + e)];
      hingeStiffness_[std::size_t(T.hinge[std::size_t(e)])] += T.weight * k;
    }
  }
  layOutHinges();
  layOutTriangles(conn);
}

void FabricBending::layOutHinges() {
  // K = Σ_T (signed B_T)ᵀ W_T (signed B_T): each triangle adds to the rows of its hinges the entries of its
  // other hinges; a hinge's row has itself and at most the two other edges of each of its two triangles.
  const std::size_t H = theta0_.size();
  std::vector<std::vector<std::pair<int, double>>> rows(H);
  for (const Triangle& T : tris_) {
    if (T.weight == 0) continue;
    const double W[3] = {T.weight, 2 * T.weight, T.weight};
    for (int e = 0; e < 3; ++e) {
      const int he = T.hinge[std::size_t(e)];
      if (he < 0) continue;
      for (int k = 0; k < 3; ++k) {
        const int hk = T.hinge[std::size_t(k)];
        if (hk < 0) continue;
        double K = 0;
        for (int r = 0; r < 3; ++r) K += T.B[std::size_t(3 * r + e)] * W[r] * T.B[std::size_t(3 * r + k)];
        K *= T.sign[std::size_t(e)] * T.sign[std::size_t(k)];
        auto& row = rows[std::size_t(he)];
        const auto it = std::find_if(row.begin(), row.end(), [&](const auto& p) { return p.first == hk; });
        if (it == row.end())
          row.emplace_back(hk, K);
        else
          it->second += K;
      }
    }
  }
  BendingHinges& B = batched_;
  constexpr int kN = BendingHinges::kNeighbours;
  B.count = int(H);
  B.padded = (B.count + kLaneWidth) / kLaneWidth * kLaneWidth;  // at least one padded lane
  const std::size_t P = std::size_t(B.padded);
  B.nodes.assign(4 * P, 0);
  B.theta0.assign(P, 0.0);
  B.stiffness.assign(P, 0.0);
  B.selfCoef.assign(P, 0.0);
  B.coef.assign(kN * P, 0.0);
  B.neighbour.assign(kN * P, 0);
  for (std::size_t h = 0; h < P; ++h) {
    // Padded lanes: the last hinge's nodes (valid addresses), no stiffness, no row: no force, no step.
    const std::size_t src = std::min(h, H - 1);
    for (std::size_t k = 0; k < 4; ++k) B.nodes[k * P + h] = H > 0 ? hingeNodes_[4 * src + k] : 0;
    B.neighbour[h] = int(h);
    for (std::size_t j = 0; j < std::size_t(kN); ++j) B.neighbour[j * P + h] = int(src);
    if (h >= H) continue;
    B.theta0[h] = theta0_[h];
    B.stiffness[h] = hingeStiffness_[h];
    std::size_t j = 0;
    for (const auto& [other, K] : rows[h]) {
      if (std::size_t(other) == h) {
        B.selfCoef[h] = K;
        continue;
      }
      if (j == std::size_t(kN)) throw std::logic_error(name() + ": a hinge with more than 4 neighbours");
      B.neighbour[j * P + h] = other;
      B.coef[j * P + h] = K;
      ++j;
    }
  }
}

void FabricBending::layOutTriangles(const std::vector<int>& conn) {
  // Each edge's triangles in interiorHinges' order (the first holds the hinge's first opposite vertex).
  std::map<std::pair<int, int>, std::vector<int>> sides;  // (lower node, higher node) -> 3 t + k
  for (std::size_t t = 0; 3 * t + 2 < conn.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = conn[3 * t + std::size_t(k)], b = conn[3 * t + std::size_t((k + 1) % 3)];
      sides[{std::min(a, b), std::max(a, b)}].push_back(int(3 * t) + k);
    }
  const std::size_t nt = conn.size() / 3;
  std::vector<std::array<int, 3>> hinge(nt, {-1, -1, -1});
  std::vector<std::array<double, 3>> sign(nt, {0, 0, 0});
  for (std::size_t h = 0; 4 * h < hingeNodes_.size(); ++h) {
    const int* n = &hingeNodes_[4 * h];
    const std::vector<int>& two = sides.at({n[2], n[3]});
    for (std::size_t side = 0; side < 2; ++side) {
      const std::size_t t = std::size_t(two[side]) / 3, k = std::size_t(two[side]) % 3;
      // hingeAngle's gradient on the side of x1 is along n1 = (x1 − x3) × (x1 − x4), on the side of x2 along
      // n2 = (x2 − x4) × (x2 − x3); the triangle's normal is (o − a) × (o − b) for its edge (a, b).
      const int a = conn[3 * t + k];
      hinge[t][k] = int(h);
      sign[t][k] = (side == 0) == (n[2] == a) ? 1.0 : -1.0;
    }
  }
  // Each triangle with the lowest of its hinges; those without a hinge have no force.
  std::vector<std::pair<int, int>> order;  // (lowest hinge, triangle)
  for (std::size_t t = 0; t < nt; ++t) {
    int lowest = -1;
    for (int h : hinge[t])
      if (h >= 0 && (lowest < 0 || h < lowest)) lowest = h;
    if (lowest >= 0) order.emplace_back(lowest, int(t));
  }
  std::sort(order.begin(), order.end());
  BendingHinges& B = batched_;
  B.triangles = int(order.size());
  B.triPadded = B.triangles + kLaneWidth;
  const std::size_t T = std::size_t(B.triPadded);
  B.triNodes.assign(3 * T, 0);
  B.triHinge.assign(3 * T, B.count);
  const int batches = B.padded / kLaneWidth;
  B.batchFirstTriangle.assign(std::size_t(batches) + 1, B.triangles);
  for (std::size_t i = order.size(); i-- > 0;) {
    const std::size_t t = std::size_t(order[i].second);
    for (std::size_t k = 0; k < 3; ++k) {
      B.triNodes[k * T + i] = conn[3 * t + k];
      const int h = hinge[t][k];
      B.triHinge[k * T + i] = h < 0 ? B.count : sign[t][k] > 0 ? h : ~h;
    }
    B.batchFirstTriangle[std::size_t(order[i].first / kLaneWidth)] = int(i);
  }
  for (int b = batches; b-- > 0;)
    B.batchFirstTriangle[std::size_t(b)] =
        std::min(B.batchFirstTriangle[std::size_t(b)], B.batchFirstTriangle[std::size_t(b) + 1]);
}

Connectivity FabricBending::connectivity() const {
  Connectivity c;
  c.items = hinges();
  c.nodesPerItem = 4;
  c.nodes = hingeNodes_.data();
  c.batch = kLaneWidth;
  c.prepass = true;
  c.prepasses = 2;
  c.scratch = batched_.scratch();
  return c;
}

double* FabricBending::scratchIn(double* memory) const {
  if (memory == nullptr)
    throw std::logic_error(name() + ": no working memory (ForceContext::scratch of " +
                           std::to_string(batched_.scratch()) + " doubles)");
  return memory;
}

std::vector<double> FabricBending::hingeAngles(const double* x) const {
  std::vector<double> dtheta(static_cast<std::size_t>(hinges()));
  for (std::size_t h = 0; h < dtheta.size(); ++h) {
    const int* n = &hingeNodes_[4 * h];
    dtheta[h] =
        wrapAngle(hingeAngle(&x[3 * n[0]], &x[3 * n[1]], &x[3 * n[2]], &x[3 * n[3]], nullptr) - theta0_[h]);
  }
  return dtheta;
}

std::array<double, 3> FabricBending::curvature(int t, const double* x) const {
  const std::vector<double> dtheta = hingeAngles(x);
  const Triangle& T = tris_[std::size_t(t)];
  std::array<double, 3> S{0, 0, 0};
  for (int e = 0; e < 3; ++e) {
    if (T.hinge[std::size_t(e)] < 0) continue;
    const double th = T.sign[std::size_t(e)] * dtheta[std::size_t(T.hinge[std::size_t(e)])];
    for (int r = 0; r < 3; ++r) S[std::size_t(r)] += T.B[std::size_t(3 * r + e)] * th;
  }
  return S;
}

void FabricBending::addForces(ForceContext& ctx) const {
  if (hinges() == 0) return;
  double* scratch = scratchIn(ctx.scratch);
  bendingAngles(batched_, mass_ != nullptr ? mass_->data() : nullptr, ctx.x, scratch, 0, hinges());
  bendingMoments(batched_, scratch, ctx.wantEnergy, 0, hinges());
  bendingForces(batched_, scratch, ctx, 0, hinges());
}

void FabricBending::prepareRange(const ForceContext& ctx, int begin, int end) const {
  if (begin >= end) return;
  if (ctx.pass == 0)
    bendingAngles(batched_, mass_ != nullptr ? mass_->data() : nullptr, ctx.x, scratchIn(ctx.scratch), begin,
                  end);
  else
    bendingMoments(batched_, scratchIn(ctx.scratch), ctx.wantEnergy, begin, end);
}

void FabricBending::addRange(ForceContext& ctx, int begin, int end) const {
  if (begin >= end) return;
  bendingForces(batched_, scratchIn(ctx.scratch), ctx, begin, end);
}

double FabricBending::energy(const double* x) const {
  const std::vector<double> dtheta = hingeAngles(x);
  double E = 0;
  for (const Triangle& T : tris_) {
    if (T.weight == 0) continue;
    double S[3] = {0, 0, 0};
    for (int e = 0; e < 3; ++e) {
      if (T.hinge[std::size_t(e)] < 0) continue;
      const double th = T.sign[std::size_t(e)] * dtheta[std::size_t(T.hinge[std::size_t(e)])];
      for (int r = 0; r < 3; ++r) S[r] += T.B[std::size_t(3 * r + e)] * th;
    }
    E += 0.5 * T.weight * (S[0] * S[0] + 2 * S[1] * S[1] + S[2] * S[2]);
  }
  return E;
}

}  // namespace fsi::structure
