#include "coupling/interface/SurfaceSearch.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "structure/model/Error.hpp"

namespace fsi::coupling {

namespace {

using Vec3 = std::array<double, 3>;

inline Vec3 sub(const double* a, const double* b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// Closest point of segment [a, b] to p as the parameter t (point = a + t (b - a)); squared distance returned.
double segmentDistance2(const double* a, const double* b, const double* p, double& t) {
  const Vec3 ab = sub(b, a), ap = sub(p, a);
  const double len2 = dot(ab, ab);
  t = len2 > 0.0 ? std::clamp(dot(ap, ab) / len2, 0.0, 1.0) : 0.0;
  const Vec3 d{ap[0] - t * ab[0], ap[1] - t * ab[1], ap[2] - t * ab[2]};
  return dot(d, d);
}

// Closest point of triangle v = (a, b, c) (9 doubles) to p, by the Voronoi region of p: a vertex, an edge or
// the interior. Returns the squared distance and the barycentric coordinates of the closest point.
double triangleDistance2(const double* v, const double* p, Vec3& bary) {
  const double* a = v;
  const double* b = v + 3;
  const double* c = v + 6;
  const Vec3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  auto finish = [&](double u, double w1, double w2) {
    bary = {u, w1, w2};
    Vec3 d;
    for (int k = 0; k < 3; ++k) d[std::size_t(k)] = p[k] - (u * a[k] + w1 * b[k] + w2 * c[k]);
    return dot(d, d);
  };
  if (d1 <= 0.0 && d2 <= 0.0) return finish(1.0, 0.0, 0.0);
  const Vec3 bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return finish(0.0, 1.0, 0.0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double t = d1 / (d1 - d3);
    return finish(1.0 - t, t, 0.0);
  }
  const Vec3 cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return finish(0.0, 0.0, 1.0);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double t = d2 / (d2 - d6);
    return finish(1.0 - t, 0.0, t);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return finish(0.0, 1.0 - t, t);
  }
  const double sum = va + vb + vc;
  if (sum > 0.0 && std::isfinite(sum)) {
    const double w1 = vb / sum, w2 = vc / sum;
    return finish(1.0 - w1 - w2, w1, w2);
  }
  // Degenerate (collinear) triangle: the closest point lies on one of its edges.
  double t0, t1, t2;
  const double e0 = segmentDistance2(a, b, p, t0), e1 = segmentDistance2(b, c, p, t1),
               e2 = segmentDistance2(c, a, p, t2);
  if (e0 <= e1 && e0 <= e2) return finish(1.0 - t0, t0, 0.0);
  if (e1 <= e2) return finish(0.0, 1.0 - t1, t1);
  return finish(t2, 0.0, 1.0 - t2);
}

inline double boxDistance2(const Vec3& lo, const Vec3& hi, const Vec3& x) {
  double d2 = 0.0;
  for (std::size_t k = 0; k < 3; ++k) {
    const double d = x[k] < lo[k] ? lo[k] - x[k] : (x[k] > hi[k] ? x[k] - hi[k] : 0.0);
    d2 += d * d;
  }
  return d2;
}

constexpr int kLeafSize = 4;

}  // namespace

FanTriangulation::FanTriangulation(const InterfaceMesh& mesh)
    : numPoints(mesh.numPoints()), faceOffsets(mesh.faceOffsets), faceNodes(mesh.faceNodes) {
  const int nf = mesh.numFaces();
  corners.reserve(std::size_t(numPoints + nf));
  corners.insert(corners.end(), mesh.points.begin(), mesh.points.end());
  for (int f = 0; f < nf; ++f) {
    const int n = mesh.faceSize(f);
    const int* v = mesh.face(f);
    if (n < 3)
      throw InputError(
          fmt::format("interface mesh '{}': face {} has {} vertices (at least 3 needed)", mesh.name, f, n));
    for (int i = 0; i < n; ++i)
      if (v[i] < 0 || v[i] >= numPoints)
        throw InputError(
            fmt::format("interface mesh '{}': face {} refers to point {}, but there are {} points", mesh.name,
                        f, v[i], numPoints));
    // Triangles of polygons get centres too (unused) so that corner ids stay numPoints + face.
    corners.push_back(mesh.faceCentroid(f));
    if (n == 3) {
      triangles.push_back({v[0], v[1], v[2]});
      triangleFace.push_back(f);
    } else {
      for (int i = 0; i < n; ++i) {
        triangles.push_back({numPoints + f, v[i], v[(i + 1) % n]});
        triangleFace.push_back(f);
      }
    }
  }
}

double FanTriangulation::interpolate(int t, const std::array<double, 3>& bary, const double* values,
                                     int components, int component) const {
  double u = 0.0;
  forEachWeight(t, bary,
                [&](int node, double w) { u += w * values[std::size_t(node) * components + component]; });
  return u;
}

std::array<double, 3> FanTriangulation::position(int t, const std::array<double, 3>& bary) const {
  const std::array<int, 3>& c = triangles[std::size_t(t)];
  std::array<double, 3> x{0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t k = 0; k < 3; ++k) x[k] += bary[i] * corners[std::size_t(c[i])][k];
  return x;
}

double FanTriangulation::area(int t) const {
  const std::array<int, 3>& c = triangles[std::size_t(t)];
  const Vec3 e1 = sub(corners[std::size_t(c[1])].data(), corners[std::size_t(c[0])].data());
  const Vec3 e2 = sub(corners[std::size_t(c[2])].data(), corners[std::size_t(c[0])].data());
  const Vec3 n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  return 0.5 * std::sqrt(dot(n, n));
}

SurfaceSearch::SurfaceSearch(const InterfaceMesh& mesh, double tolerance)
    : fan_(mesh), tolerance_(tolerance) {
  const int nt = fan_.numTriangles();
  if (nt == 0) throw InputError(fmt::format("interface mesh '{}' has no faces to search", mesh.name));
  std::vector<Vec3> centroids(static_cast<std::size_t>(nt));
  for (int t = 0; t < nt; ++t) centroids[std::size_t(t)] = fan_.position(t, {1.0 / 3, 1.0 / 3, 1.0 / 3});
  order_.resize(std::size_t(nt));
  for (int t = 0; t < nt; ++t) order_[std::size_t(t)] = t;
  // A binary tree with at least one triangle per leaf has fewer than 2 nt nodes: no reallocation below.
  nodes_.reserve(std::size_t(2 * nt));
  nodes_.push_back({});
  build(0, 0, nt, centroids);
  slotOf_.resize(std::size_t(nt));
  vertices_.resize(std::size_t(nt));
  for (int s = 0; s < nt; ++s) {
    const int t = order_[std::size_t(s)];
    slotOf_[std::size_t(t)] = s;
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t k = 0; k < 3; ++k)
        vertices_[std::size_t(s)][3 * i + k] =
            fan_.corners[std::size_t(fan_.triangles[std::size_t(t)][i])][k];
  }
}

// Fills node `self`, which covers order_[begin, end), and its subtree.
void SurfaceSearch::build(int self, int begin, int end, const std::vector<Vec3>& centroids) {
  Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  Vec3 clo = lo, chi = hi;
  for (int s = begin; s < end; ++s) {
    const int t = order_[std::size_t(s)];
    for (int c : fan_.triangles[std::size_t(t)])
      for (std::size_t k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], fan_.corners[std::size_t(c)][k]);
        hi[k] = std::max(hi[k], fan_.corners[std::size_t(c)][k]);
      }
    for (std::size_t k = 0; k < 3; ++k) {
      clo[k] = std::min(clo[k], centroids[std::size_t(t)][k]);
      chi[k] = std::max(chi[k], centroids[std::size_t(t)][k]);
    }
  }
  nodes_[std::size_t(self)].lo = lo;
  nodes_[std::size_t(self)].hi = hi;
  if (end - begin <= kLeafSize) {
    nodes_[std::size_t(self)].first = begin;
    nodes_[std::size_t(self)].count = end - begin;
    return;
  }
  // Median split along the widest spread of centroids: balanced, so depth ≤ log2(N) and setup O(N log N).
  std::size_t axis = 0;
  for (std::size_t k = 1; k < 3; ++k)
    if (chi[k] - clo[k] > chi[axis] - clo[axis]) axis = k;
  const int mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end, [&](int a, int b) {
    return centroids[std::size_t(a)][axis] < centroids[std::size_t(b)][axis];
  });
  const int left = int(nodes_.size());
  nodes_[std::size_t(self)].first = left;
  nodes_[std::size_t(self)].count = 0;
  nodes_.push_back({});
  nodes_.push_back({});
  build(left, begin, mid, centroids);
  build(left + 1, mid, end, centroids);
}

double SurfaceSearch::distance2(int slot, const std::array<double, 3>& x, std::array<double, 3>& bary) const {
  return triangleDistance2(vertices_[std::size_t(slot)].data(), x.data(), bary);
}

template <class Accept>
SurfacePoint SurfaceSearch::search(const std::array<double, 3>& x, int hint, Accept&& accept) const {
  double best2 = HUGE_VAL;
  int bestSlot = -1;
  Vec3 bestBary{}, bary;
  if (hint >= 0 && hint < fan_.numTriangles()) {
    const int slot = slotOf_[std::size_t(hint)];
    if (accept(slot)) {
      bestSlot = slot;
      best2 = distance2(bestSlot, x, bestBary);
    }
  }
  struct Entry {
    int node;
    double d2;
  };
  Entry stack[128];
  int top = 0;
  stack[top++] = {0, boxDistance2(nodes_[0].lo, nodes_[0].hi, x)};
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.d2 >= best2) continue;
    const BoxNode& n = nodes_[std::size_t(e.node)];
    if (n.count > 0) {
      for (int s = n.first; s < n.first + n.count; ++s) {
        if (!accept(s)) continue;
        const double d2 = distance2(s, x, bary);
        if (d2 < best2) {
          best2 = d2;
          bestSlot = s;
          bestBary = bary;
        }
      }
      continue;
    }
    const int l = n.first, r = n.first + 1;
    const double dl = boxDistance2(nodes_[std::size_t(l)].lo, nodes_[std::size_t(l)].hi, x);
    const double dr = boxDistance2(nodes_[std::size_t(r)].lo, nodes_[std::size_t(r)].hi, x);
    // Push the farther child first so the nearer one is explored first and tightens the bound.
    if (dl <= dr) {
      if (dr < best2) stack[top++] = {r, dr};
      if (dl < best2) stack[top++] = {l, dl};
    } else {
      if (dl < best2) stack[top++] = {l, dl};
      if (dr < best2) stack[top++] = {r, dr};
    }
  }
  SurfacePoint p;
  if (bestSlot < 0) return p;  // nothing accepted: unmapped, at infinite distance
  p.triangle = order_[std::size_t(bestSlot)];
  p.face = fan_.triangleFace[std::size_t(p.triangle)];
  p.bary = bestBary;
  p.point = fan_.position(p.triangle, bestBary);
  p.distance = std::sqrt(best2);
  p.mapped = p.distance <= tolerance_;
  return p;
}

SurfacePoint SurfaceSearch::closest(const std::array<double, 3>& x, int hint) const {
  return search(x, hint, [](int) { return true; });
}

std::vector<SurfacePoint> SurfaceSearch::equallyClose(const std::array<double, 3>& x,
                                                      const SurfacePoint& best) const {
  std::vector<SurfacePoint> out{best};
  if (best.triangle < 0) return out;
  // Round-off of a distance computed on two mirror-image triangles, relative to the surface's size.
  const Vec3 diag = sub(nodes_[0].hi.data(), nodes_[0].lo.data());
  const double tiny2 = 1e-24 * dot(diag, diag);
  const double bound2 = best.distance * best.distance * (1.0 + 1e-9) + tiny2;
  std::vector<int> stack{0};
  std::array<double, 3> bary;
  while (!stack.empty()) {
    const BoxNode& n = nodes_[std::size_t(stack.back())];
    stack.pop_back();
    if (boxDistance2(n.lo, n.hi, x) > bound2) continue;
    if (n.count == 0) {
      stack.push_back(n.first);
      stack.push_back(n.first + 1);
      continue;
    }
    for (int s = n.first; s < n.first + n.count; ++s) {
      const double d2 = distance2(s, x, bary);
      if (d2 > bound2) continue;
      const int t = order_[std::size_t(s)];
      const std::array<double, 3> at = fan_.position(t, bary);
      const bool seen = std::any_of(out.begin(), out.end(), [&](const SurfacePoint& q) {
        const Vec3 d = sub(q.point.data(), at.data());
        return dot(d, d) <= tiny2;
      });
      if (seen) continue;
      SurfacePoint p;
      p.triangle = t;
      p.face = fan_.triangleFace[std::size_t(t)];
      p.bary = bary;
      p.point = at;
      p.distance = std::sqrt(d2);
      p.mapped = p.distance <= tolerance_;
      out.push_back(p);
    }
  }
  return out;
}

std::array<double, 3> SurfaceSearch::normal(int t) const {
  return slotNormal(slotOf_[std::size_t(t)]);
}

std::array<double, 3> SurfaceSearch::slotNormal(int slot) const {
  const double* v = vertices_[std::size_t(slot)].data();
  const Vec3 a = sub(v + 3, v), b = sub(v + 6, v);
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

SurfacePoint SurfaceSearch::closestFacing(const std::array<double, 3>& x, const std::array<double, 3>& facing,
                                          int hint) const {
  // Round-off must not make a face at right angles to `facing` count as facing that way.
  const double f = std::sqrt(dot(facing, facing)) * kPerpendicular;
  return search(x, hint, [&](int slot) {
    const Vec3 n = slotNormal(slot);
    return dot(n, facing) > f * std::sqrt(dot(n, n));
  });
}

}  // namespace fsi::coupling
