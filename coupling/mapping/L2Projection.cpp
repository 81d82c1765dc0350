#include "coupling/mapping/L2Projection.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "structure/model/Error.hpp"

namespace fsi::coupling {

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// A target quadrature point: barycentric point of a target fan triangle and its (summed) weight.
struct QuadPoint {
  int triangle;
  std::array<double, 3> bary;
  double weight;
};

// Edge-midpoint rule on the level² sub-triangles of every target fan triangle. The rule's points are the
// lattice points (I, J, K)/(2 level), I + J + K = 2 level, with exactly two odd coordinates; a point on a fan
// triangle's edge is shared with the neighbour across that edge, so it is created once (by the first
// triangle) and its weights summed, which halves the searches for level 1.
// With `perTriangle`, also records every triangle's own (point, weight) pairs, 3 level (level + 1) / 2 per
// triangle in triangle order, for test functions that are discontinuous between faces.
std::vector<QuadPoint> quadraturePoints(const FanTriangulation& fan, int level,
                                        std::vector<std::pair<int, double>>* perTriangle) {
  const int nt = fan.numTriangles();
  const int nc = int(fan.corners.size());
  // Corner → triangles, to find the earlier neighbour across an edge.
  std::vector<int> start(std::size_t(nc) + 1, 0), tris(std::size_t(3 * nt));
  for (const auto& c : fan.triangles)
    for (int k : c) ++start[std::size_t(k) + 1];
  for (int k = 0; k < nc; ++k) start[std::size_t(k) + 1] += start[std::size_t(k)];
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int t = 0; t < nt; ++t)
      for (int k : fan.triangles[std::size_t(t)]) tris[std::size_t(fill[std::size_t(k)]++)] = t;
  }
  const int s = level, twoS = 2 * level;
  std::vector<QuadPoint> qp;
  qp.reserve(std::size_t(nt) * std::size_t(3 * s * (s + 1) / 2) / 2 + 16);
  std::vector<int> edgeBase(std::size_t(3 * nt), -1);
  for (int t = 0; t < nt; ++t) {
    const std::array<int, 3>& c = fan.triangles[std::size_t(t)];
    const double wSub = fan.area(t) / (3.0 * s * s);
    for (int e = 0; e < 3; ++e) {
      const int a = c[std::size_t(e)], b = c[std::size_t((e + 1) % 3)];
      int base = -1;
      for (int p = start[std::size_t(a)]; p < start[std::size_t(a) + 1] && base < 0; ++p) {
        const int t2 = tris[std::size_t(p)];
        if (t2 >= t) continue;
        const std::array<int, 3>& c2 = fan.triangles[std::size_t(t2)];
        for (int e2 = 0; e2 < 3; ++e2) {
          const int a2 = c2[std::size_t(e2)], b2 = c2[std::size_t((e2 + 1) % 3)];
          if ((a2 == a && b2 == b) || (a2 == b && b2 == a)) {
            base = edgeBase[std::size_t(3 * t2 + e2)];
            break;
          }
        }
      }
      if (base < 0) {
        base = int(qp.size());
        // Points ordered from the smaller corner id, so that both neighbours agree on them.
        const bool aFirst = a < b;
        for (int k = 0; k < s; ++k) {
          const double frac = double(2 * k + 1) / twoS;  // distance from the smaller corner
          std::array<double, 3> bary{0.0, 0.0, 0.0};
          bary[std::size_t(e)] = aFirst ? 1.0 - frac : frac;
          bary[std::size_t((e + 1) % 3)] = aFirst ? frac : 1.0 - frac;
          qp.push_back({t, bary, 0.0});
        }
      }
      edgeBase[std::size_t(3 * t + e)] = base;
      for (int k = 0; k < s; ++k) {
        qp[std::size_t(base + k)].weight += wSub;
        if (perTriangle) perTriangle->push_back({base + k, wSub});
      }
    }
    for (int i = 1; i < twoS; ++i)
      for (int j = 1; i + j < twoS; ++j) {
        const int k = twoS - i - j;
        if ((i % 2) + (j % 2) + (k % 2) != 2) continue;
        qp.push_back({t, {double(i) / twoS, double(j) / twoS, double(k) / twoS}, 2.0 * wSub});
        if (perTriangle) perTriangle->push_back({int(qp.size()) - 1, 2.0 * wSub});
      }
  }
  return qp;
}

// Sparse accumulator for one row: dense values plus the list of touched columns.
struct RowAccumulator {
  explicit RowAccumulator(int n) : value(std::size_t(n), 0.0), mark(std::size_t(n), -1) {}
  void add(int row, int col, double v) {
    if (mark[std::size_t(col)] != row) {
      mark[std::size_t(col)] = row;
      value[std::size_t(col)] = 0.0;
      touched.push_back(col);
    }
    value[std::size_t(col)] += v;
  }
  // Appends the row (sorted columns) to CSR arrays and resets.
  void emit(std::vector<int>& inner, std::vector<double>& values) {
    std::sort(touched.begin(), touched.end());
    for (int col : touched) {
      inner.push_back(col);
      values.push_back(value[std::size_t(col)]);
    }
    touched.clear();
  }
  void discard() {
    for (int col : touched) mark[std::size_t(col)] = -1;
    touched.clear();
  }
  std::vector<double> value;
  std::vector<int> mark, touched;
};

// First-order transport of the source field across the gap between the two discrete surfaces. Where they
// do not coincide (a curved surface meshed twice: each mesh's chords lie inside the surface by up to
// h²/8R), a target quadrature point x and its closest source point P(x) are a gap d = x − P(x) apart, and a
// field varying along the normal differs there by d·∇f: the source value at P(x) is the wrong value for x.
// For a field linear in x, y, z the L2 projection then maps even the coordinates with an O(h²) error (so a
// rigid rotation is distorted and Hᵀ does not conserve the moment), and a coarse target is biased by its
// own chord gap h_t²/8R, ~(h_t/h_s)² times the error of nearest-point interpolation from a finer source.
// The fix evaluates f(P(x)) + d·∇f instead, with ∇f the gradient of the least-squares fit
// a + b·(y − c) of the source values over the nodes of the faces around the source triangle's nodes:
// ∇f = Σ_j g_j f_j with Σ_j g_j = 0 (constants, so row sums and the total force are unchanged) and
// Σ_j g_j x_jᵀ = I (exact for linear fields). The surface's own curvature is what makes the normal
// derivative observable; on a flat neighbourhood it is not, and only the tangential part is used (the gap
// of two coinciding flat surfaces is zero anyway).
class GapGradient {
 public:
  struct Entry {
    int node;
    std::array<double, 3> g;
  };

  GapGradient(const InterfaceMesh& mesh, const FanTriangulation& fan, double minRadius)
      : mesh_(mesh),
        fan_(fan),
        minRadius_(minRadius),
        start_(std::size_t(fan.numTriangles()) + 1, -1),
        mark_(mesh.points.size(), -1) {
    const int np = mesh.numPoints();
    nodeFaceStart_.assign(std::size_t(np) + 1, 0);
    for (int n : mesh.faceNodes) ++nodeFaceStart_[std::size_t(n) + 1];
    for (int i = 0; i < np; ++i) nodeFaceStart_[std::size_t(i) + 1] += nodeFaceStart_[std::size_t(i)];
    nodeFaces_.resize(mesh.faceNodes.size());
    std::vector<int> fill(nodeFaceStart_.begin(), nodeFaceStart_.end() - 1);
    for (int f = 0; f < mesh.numFaces(); ++f)
      for (int k = 0; k < mesh.faceSize(f); ++k)
        nodeFaces_[std::size_t(fill[std::size_t(mesh.face(f)[k])]++)] = f;
    // Newell's normal of every face (any polygon), for keeping a patch on its own side of a fold.
    faceNormal_.resize(std::size_t(mesh.numFaces()));
    for (int f = 0; f < mesh.numFaces(); ++f) {
      Eigen::Vector3d n = Eigen::Vector3d::Zero();
      for (int k = 0; k < mesh.faceSize(f); ++k) {
        const Eigen::Vector3d a(mesh.points[std::size_t(mesh.face(f)[k])].data()),
            b(mesh.points[std::size_t(mesh.face(f)[(k + 1) % mesh.faceSize(f)])].data());
        n += a.cross(b);
      }
      faceNormal_[std::size_t(f)] = n;
    }
  }

  // Builds the stencils of the triangles flagged in `used`, in triangle order.
  void build(const std::vector<unsigned char>& used) {
    for (int t = 0; t < fan_.numTriangles(); ++t) {
      start_[std::size_t(t)] = int(entries_.size());
      if (used[std::size_t(t)]) buildOne(t);
    }
    start_.back() = int(entries_.size());
  }
  const Entry* begin(int t) const { return entries_.data() + start_[std::size_t(t)]; }
  const Entry* end(int t) const { return entries_.data() + start_[std::size_t(t) + 1]; }
  long flatTriangles = 0;

 private:
  void buildOne(int t) {
    // The triangle's nodes (a polygon centre stands for its face's nodes), then every node of their faces.
    patch_.clear();
    auto addNode = [&](int n) {
      if (mark_[std::size_t(n)] != t) {
        mark_[std::size_t(n)] = t;
        patch_.push_back(n);
      }
    };
    std::vector<int> own;
    for (int c : fan_.triangles[std::size_t(t)]) {
      if (c < fan_.numPoints) {
        own.push_back(c);
      } else {
        const int f = c - fan_.numPoints;
        for (int k = 0; k < mesh_.faceSize(f); ++k) own.push_back(mesh_.face(f)[k]);
      }
    }
    for (int n : own) addNode(n);
    const auto& c = fan_.triangles[std::size_t(t)];
    const Eigen::Vector3d p0(fan_.corners[std::size_t(c[0])].data()),
        p1(fan_.corners[std::size_t(c[1])].data()), p2(fan_.corners[std::size_t(c[2])].data());
    const Eigen::Vector3d centre = (p0 + p1 + p2) / 3.0;
    const Eigen::Vector3d facing = (p1 - p0).cross(p2 - p0);
    // Rings of faces around the triangle until the patch reaches minRadius_ (at least one ring). Only faces
    // on the triangle's own side of a fold (normals less than 90° apart) join: at a trailing edge the other
    // skin is a different surface, and a field (the displacement of a skin that bulges while the other
    // flattens) need not be one smooth function across the edge.
    std::size_t done = 0;
    for (int ring = 0; ring < kMaxRings && patch_.size() < kMaxPatch; ++ring) {
      const std::size_t count = patch_.size();
      for (std::size_t a = done; a < count; ++a) {
        const int n = patch_[a];
        for (int p = nodeFaceStart_[std::size_t(n)]; p < nodeFaceStart_[std::size_t(n) + 1]; ++p) {
          const int f = nodeFaces_[std::size_t(p)];
          const Eigen::Vector3d& nf = faceNormal_[std::size_t(f)];
          if (!(nf.dot(facing) > kPerpendicular * nf.norm() * facing.norm())) continue;
          for (int k = 0; k < mesh_.faceSize(f); ++k) addNode(mesh_.face(f)[k]);
        }
      }
      done = count;
      double reach = 0.0;
      for (std::size_t a = count; a < patch_.size(); ++a)
        reach =
            std::max(reach, (Eigen::Vector3d(mesh_.points[std::size_t(patch_[a])].data()) - centre).norm());
      if (patch_.size() == count || reach >= minRadius_) break;
    }
    // Local frame: the triangle's tangents and normal, centred on the patch, scaled by its radius, so that
    // the normal equations are well scaled and the flatness test is relative.
    Eigen::Vector3d n = (p1 - p0).cross(p2 - p0);
    if (!(n.norm() > 0.0) || (p1 - p0).norm() == 0.0) return;  // degenerate triangle: no correction
    n.normalize();
    const Eigen::Vector3d t1 = (p1 - p0).normalized(), t2 = n.cross(t1);
    double radius = 0.0;
    for (int j : patch_)
      radius = std::max(radius, (Eigen::Vector3d(mesh_.points[std::size_t(j)].data()) - centre).norm());
    if (!(radius > 0.0)) return;
    Eigen::Matrix<double, 4, Eigen::Dynamic> r(4, long(patch_.size()));
    Eigen::VectorXd w(long(patch_.size()));
    for (std::size_t j = 0; j < patch_.size(); ++j) {
      const Eigen::Vector3d y =
          (Eigen::Vector3d(mesh_.points[std::size_t(patch_[j])].data()) - centre) / radius;
      r.col(long(j)) << 1.0, y.dot(t1), y.dot(t2), y.dot(n);
      // Weights falling smoothly to ~0 at the patch's edge: neighbouring triangles' fits then differ
      // little, so Hᵀ stays smooth (hard-edged patches left 16-80 % RMS noise in a uniform pressure).
      const double q = 1.0 - y.squaredNorm() / 1.1025;
      w(long(j)) = q * q;
    }
    const Eigen::Matrix4d a = r * w.asDiagonal() * r.transpose();
    const Eigen::Matrix3d a3 = a.topLeftCorner<3, 3>();  // weighted
    const Eigen::LLT<Eigen::Matrix3d> llt3(a3);
    if (llt3.info() != Eigen::Success) return;
    // Normal spread left after fitting the tangential plane (the Schur complement of the normal
    // coordinate): zero on a flat patch, ~(radius / 2R)² × nodes on a sphere of radius R.
    const double schur = a(3, 3) - a.block<1, 3>(3, 0) * llt3.solve(a.block<3, 1>(0, 3));
    Eigen::Matrix<double, 3, Eigen::Dynamic> g;  // gradient weights in the frame (t1, t2, n), per radius
    if (schur > 1e-12 * double(patch_.size())) {
      g = a.inverse().bottomRows<3>() * r * w.asDiagonal();
    } else {
      ++flatTriangles;
      g.setZero(3, long(patch_.size()));
      g.topRows<2>() = llt3.solve(r.topRows<3>() * w.asDiagonal()).bottomRows<2>();
    }
    for (std::size_t j = 0; j < patch_.size(); ++j) {
      const Eigen::Vector3d gj = (g(0, long(j)) * t1 + g(1, long(j)) * t2 + g(2, long(j)) * n) / radius;
      entries_.push_back({patch_[j], {gj.x(), gj.y(), gj.z()}});
    }
  }

  // Bounds on a patch: the stencils are stored for every source triangle hit (32 bytes per patch node), so a
  // target many times coarser than the source must not make them grow as the ratio squared; beyond these
  // the fit is noisier (Hᵀ less smooth), never inexact.
  static constexpr int kMaxRings = 16;
  static constexpr std::size_t kMaxPatch = 256;

 public:
  long entries() const { return long(entries_.size()); }

 private:
  const InterfaceMesh& mesh_;
  const FanTriangulation& fan_;
  double minRadius_;
  std::vector<int> start_, mark_, nodeFaceStart_, nodeFaces_, patch_;
  std::vector<Eigen::Vector3d> faceNormal_;
  std::vector<Entry> entries_;
};

L2Projection::SparseRows fromCsr(int rows, int cols, const std::vector<int>& outer,
                                 const std::vector<int>& inner, const std::vector<double>& values) {
  const Eigen::Map<const L2Projection::SparseRows> map(rows, cols, long(values.size()), outer.data(),
                                                       inner.data(), values.data());
  return L2Projection::SparseRows(map);
}

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}

// Unnormalised normal of fan triangle t (by its corner order).
Eigen::Vector3d fanNormal(const FanTriangulation& fan, int t) {
  const auto& c = fan.triangles[std::size_t(t)];
  const Eigen::Vector3d p0(fan.corners[std::size_t(c[0])].data()), p1(fan.corners[std::size_t(c[1])].data()),
      p2(fan.corners[std::size_t(c[2])].data());
  return (p1 - p0).cross(p2 - p0);
}

// ProjectionOptions::keepSide. The sign of n_target · n_source over the mapped points, weighted by their
// area, tells how the two meshes' orientations relate (OpenFOAM's patch normals point into the body, a
// structure's skin may point out: −1 then) and whether the interface is wetted from one side. If it is, the
// points of the minority sign sit where the closest source triangle belongs to the other side of the body
// (the two skins of a trailing edge meet at a smaller angle than the meshes' gap resolves); each is searched
// again among the triangles facing its own way. `gap` (x − P(x)) is updated when it is kept (non-empty).
void keepSides(const SurfaceSearch& search, const FanTriangulation& tf, const std::vector<QuadPoint>& qp,
               std::vector<int>& srcTri, std::vector<std::array<double, 3>>& srcBary,
               std::vector<std::array<double, 3>>& gap, ProjectionReport& report) {
  const long nq = long(qp.size());
  std::vector<signed char> sign(std::size_t(nq), 0);
  double positive = 0.0, negative = 0.0;
  for (long q = 0; q < nq; ++q) {
    const int s = srcTri[std::size_t(q)];
    if (s < 0) continue;
    const Eigen::Vector3d ns(search.normal(s).data()), nt = fanNormal(tf, qp[std::size_t(q)].triangle);
    // Faces at right angles (a skin against an end cap) have no side: their cosine is round-off.
    const double d = nt.dot(ns), scale = kPerpendicular * nt.norm() * ns.norm();
    if (d > scale) {
      sign[std::size_t(q)] = 1;
      positive += qp[std::size_t(q)].weight;
    } else if (d < -scale) {
      sign[std::size_t(q)] = -1;
      negative += qp[std::size_t(q)].weight;
    }
  }
  const double total = positive + negative;
  if (!(total > 0.0)) return;
  report.facingShare = std::max(positive, negative) / total;
  report.oneSided = report.facingShare >= kOneSidedShare;
  if (!report.oneSided) return;
  const signed char majority = positive >= negative ? 1 : -1;
  // The meshes' own gap scale: the largest distance of a point that faces the right way. A point whose own
  // side is farther than that is not at a thin edge but on a face that is itself turned over (snapped
  // faces at a sharp corner can be): moving it would tear it from the surface it belongs to.
  double ownGap = 0.0;
  for (long q = 0; q < nq; ++q) {
    if (sign[std::size_t(q)] != majority) continue;
    const QuadPoint& p = qp[std::size_t(q)];
    const std::array<double, 3> x = tf.position(p.triangle, p.bary);
    ownGap =
        std::max(ownGap, distance(x, search.fan().position(srcTri[std::size_t(q)], srcBary[std::size_t(q)])));
  }
  for (long q = 0; q < nq; ++q) {
    if (sign[std::size_t(q)] != -majority) continue;
    const QuadPoint& p = qp[std::size_t(q)];
    const Eigen::Vector3d facing = double(majority) * fanNormal(tf, p.triangle);
    const std::array<double, 3> x = tf.position(p.triangle, p.bary);
    const SurfacePoint r = search.closestFacing(x, {facing.x(), facing.y(), facing.z()});
    // Beyond the tolerance or the meshes' gap (or no triangle facing that way): keep the closest one.
    if (!r.mapped || r.distance > ownGap) {
      ++report.turnedPoints;
      continue;
    }
    srcTri[std::size_t(q)] = r.triangle;
    srcBary[std::size_t(q)] = r.bary;
    if (!gap.empty()) gap[std::size_t(q)] = {x[0] - r.point[0], x[1] - r.point[1], x[2] - r.point[2]};
    report.maxGap = std::max(report.maxGap, r.distance);
    report.maxResidedGap = std::max(report.maxResidedGap, r.distance);
    ++report.residedPoints;
  }
}

}  // namespace

L2Projection::L2Projection(const InterfaceMesh& source, const InterfaceMesh& target,
                           const ProjectionOptions& options)
    : ns_(source.numPoints()), nt_(target.numPoints()), mass_(resolveMass(options.mass, target.numPoints())) {
  const auto tSetup = Clock::now();
  report_.source = source.name;
  report_.target = target.name;
  report_.sourceNodes = ns_;
  report_.targetNodes = nt_;

  auto t0 = Clock::now();
  const SurfaceSearch search(source, options.tolerance);
  const FanTriangulation tf(target);
  report_.targetTriangles = tf.numTriangles();
  const int level = options.quadratureLevel == kAutoQuadrature ? autoQuadratureLevel(source, target)
                                                               : std::max(1, options.quadratureLevel);
  report_.quadratureLevel = level;
  std::vector<std::pair<int, double>> perTriangle;
  const std::vector<QuadPoint> qp =
      quadraturePoints(tf, level, mass_ == MassMatrix::Dual ? &perTriangle : nullptr);
  const long nq = long(qp.size());
  report_.quadraturePoints = nq;

  // Closest source point of every quadrature point; consecutive points are neighbours, so the previous
  // answer is a tight initial bound for the next search.
  std::vector<int> srcTri(std::size_t(nq), -1);
  std::vector<std::array<double, 3>> srcBary(static_cast<std::size_t>(nq));
  std::vector<std::array<double, 3>> gap(options.gapCorrection ? std::size_t(nq) : 0);  // x − P(x)
  int hint = -1;
  for (long q = 0; q < nq; ++q) {
    const std::array<double, 3> x = tf.position(qp[std::size_t(q)].triangle, qp[std::size_t(q)].bary);
    const SurfacePoint p = search.closest(x, hint);
    hint = p.triangle;
    if (p.mapped) {
      srcTri[std::size_t(q)] = p.triangle;
      srcBary[std::size_t(q)] = p.bary;
      if (options.gapCorrection)
        gap[std::size_t(q)] = {x[0] - p.point[0], x[1] - p.point[1], x[2] - p.point[2]};
      report_.maxGap = std::max(report_.maxGap, p.distance);
    } else {
      if (report_.firstUnmappedPoints.size() < ProjectionReport::kListed)
        report_.firstUnmappedPoints.push_back({q, x, p.distance});
      ++report_.unmappedQuadraturePoints;
    }
  }
  if (options.keepSide) keepSides(search, tf, qp, srcTri, srcBary, gap, report_);
  report_.searchSeconds = secondsSince(t0);

  t0 = Clock::now();
  const FanTriangulation& sf = search.fan();
  // The patch reaches 2 × the larger mean edge: the fitted normal derivative is then well determined
  // against the gaps (which grow as the coarser mesh's h²), see GapGradient.
  const double sourceEdge = source.meanEdgeLength();
  GapGradient gradient(source, sf, 2.0 * std::max(sourceEdge, target.meanEdgeLength()));
  report_.gapCorrection = options.gapCorrection;
  // Coinciding surfaces: a gap at round-off would only add entries of round-off size to C.
  const auto negligible = [&](const std::array<double, 3>& d) {
    return std::abs(d[0]) + std::abs(d[1]) + std::abs(d[2]) <= 1e-12 * sourceEdge;
  };
  if (options.gapCorrection) {
    // Stencils only where a point has a gap (none on coinciding flat surfaces: no cost there).
    std::vector<unsigned char> used(std::size_t(sf.numTriangles()), 0);
    for (long q = 0; q < nq; ++q)
      if (srcTri[std::size_t(q)] >= 0 && !negligible(gap[std::size_t(q)]))
        used[std::size_t(srcTri[std::size_t(q)])] = 1;
    gradient.build(used);
    report_.flatGradientTriangles = gradient.flatTriangles;
    report_.gapStencilEntries = gradient.entries();
  }
  // Adds w × (the source functions at quadrature point q, moved across the gap) to row i of C.
  auto addSource = [&](RowAccumulator& acc, int i, long q, double w) {
    const int t = srcTri[std::size_t(q)];
    sf.forEachWeight(t, srcBary[std::size_t(q)], [&](int k, double phi) { acc.add(i, k, w * phi); });
    if (!options.gapCorrection) return;
    const std::array<double, 3>& d = gap[std::size_t(q)];
    if (negligible(d)) return;
    for (const GapGradient::Entry* e = gradient.begin(t); e != gradient.end(t); ++e)
      acc.add(i, e->node, w * (d[0] * e->g[0] + d[1] * e->g[1] + d[2] * e->g[2]));
  };
  RowAccumulator accM(nt_), accC(ns_);
  std::vector<int> mOuter{0}, mInner, cOuter{0}, cInner;
  std::vector<double> mValues, cValues;
  mOuter.reserve(std::size_t(nt_) + 1);
  cOuter.reserve(std::size_t(nt_) + 1);
  lumped_.resize(nt_);
  nodeMapped_.assign(std::size_t(nt_), 1);
  // Closes row i of M_t and C; rowSum = ∫ N_i.
  auto finishRow = [&](int i, double rowSum, bool unmapped) {
    if (!(rowSum > 0.0)) {
      // No support of positive area: the node gets no value (0). A unit diagonal keeps M_t definite.
      unmapped = true;
      accM.discard();
      accC.discard();
      if (mass_ == MassMatrix::Consistent) accM.add(i, i, 1.0);
      rowSum = 0.0;
    }
    lumped_[i] = rowSum;
    accM.emit(mInner, mValues);
    accC.emit(cInner, cValues);
    mOuter.push_back(int(mInner.size()));
    cOuter.push_back(int(cInner.size()));
    if (unmapped) {
      nodeMapped_[std::size_t(i)] = 0;
      if (report_.firstUnmappedNodes.size() < ProjectionReport::kListed)
        report_.firstUnmappedNodes.push_back(i);
      ++report_.unmappedTargetNodes;
    }
  };

  if (mass_ != MassMatrix::Dual) {
    // Target node → (quadrature point, N_i there), in CSR form, so that each row of M_t and C is assembled
    // in one pass with a sparse accumulator (memory ∝ nnz, no triplet lists).
    std::vector<int> adjStart(std::size_t(nt_) + 1, 0);
    for (const QuadPoint& p : qp)
      tf.forEachWeight(p.triangle, p.bary, [&](int i, double) { ++adjStart[std::size_t(i) + 1]; });
    for (int i = 0; i < nt_; ++i) adjStart[std::size_t(i) + 1] += adjStart[std::size_t(i)];
    std::vector<int> adjPoint(std::size_t(adjStart.back()));
    std::vector<double> adjN(std::size_t(adjStart.back()));
    {
      std::vector<int> fill(adjStart.begin(), adjStart.end() - 1);
      for (long q = 0; q < nq; ++q) {
        const QuadPoint& p = qp[std::size_t(q)];
        tf.forEachWeight(p.triangle, p.bary, [&](int i, double n) {
          const int slot = fill[std::size_t(i)]++;
          adjPoint[std::size_t(slot)] = int(q);
          adjN[std::size_t(slot)] = n;
        });
      }
    }
    for (int i = 0; i < nt_; ++i) {
      double rowSum = 0.0;
      bool unmapped = false;
      for (int a = adjStart[std::size_t(i)]; a < adjStart[std::size_t(i) + 1]; ++a) {
        const int q = adjPoint[std::size_t(a)];
        const QuadPoint& p = qp[std::size_t(q)];
        const double wi = p.weight * adjN[std::size_t(a)];
        rowSum += wi;
        tf.forEachWeight(p.triangle, p.bary, [&](int j, double n) { accM.add(i, j, wi * n); });
        if (srcTri[std::size_t(q)] >= 0)
          addSource(accC, i, q, wi);
        else
          unmapped = true;
      }
      finishRow(i, rowSum, unmapped);
    }
  } else {
    // Dual (biorthogonal) test functions: on face f, ψ_a = Σ_b A_f,ab N_b with A_f = D_f M_f⁻¹ (M_f the
    // face's mass matrix, D_f its row sums), so that ∫_f ψ_a N_b = δ_ab ∫_f N_a. The projection's mass matrix
    // is then exactly diagonal, H = D⁻¹ C_ψ is as sparse as C, and every field of the target space is still
    // reproduced (Σ_a ψ_a = 1 and ∫ψ_a = ∫N_a on every face).
    const int nf = target.numFaces();
    std::vector<int> faceTri(std::size_t(nf) + 1, 0);  // fan triangles of a face are consecutive
    for (int t = 0; t < tf.numTriangles(); ++t) ++faceTri[std::size_t(tf.triangleFace[std::size_t(t)]) + 1];
    for (int f = 0; f < nf; ++f) faceTri[std::size_t(f) + 1] += faceTri[std::size_t(f)];
    std::vector<int> nodeFaceStart(std::size_t(nt_) + 1, 0), nodeFaces(target.faceNodes.size());
    for (int n : target.faceNodes) ++nodeFaceStart[std::size_t(n) + 1];
    for (int i = 0; i < nt_; ++i) nodeFaceStart[std::size_t(i) + 1] += nodeFaceStart[std::size_t(i)];
    {
      std::vector<int> fill(nodeFaceStart.begin(), nodeFaceStart.end() - 1);
      for (int f = 0; f < nf; ++f)
        for (int k = 0; k < target.faceSize(f); ++k)
          nodeFaces[std::size_t(fill[std::size_t(target.face(f)[k])]++)] = f;
    }
    // A_f (row-major, n_f² values) and D_f (n_f values, aligned with the face's nodes) for every face.
    std::vector<std::size_t> aOffset(std::size_t(nf) + 1, 0);
    for (int f = 0; f < nf; ++f)
      aOffset[std::size_t(f) + 1] =
          aOffset[std::size_t(f)] + std::size_t(target.faceSize(f) * target.faceSize(f));
    std::vector<double> aValues(aOffset.back(), 0.0), dValues(target.faceNodes.size(), 0.0);
    Eigen::MatrixXd mf, minv;
    Eigen::VectorXd df;
    for (int f = 0; f < nf; ++f) {
      const int n = target.faceSize(f);
      const int* nodes = target.face(f);
      mf.setZero(n, n);
      for (int t = faceTri[std::size_t(f)]; t < faceTri[std::size_t(f) + 1]; ++t) {
        // Corner k of the fan triangle as weights over the face's nodes: one node, or 1/n each for the
        // centre.
        Eigen::Matrix<double, 3, Eigen::Dynamic> e = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, n);
        for (int k = 0; k < 3; ++k) {
          const int c = tf.triangles[std::size_t(t)][std::size_t(k)];
          if (c >= tf.numPoints) {
            e.row(k).setConstant(1.0 / n);
          } else {
            for (int b = 0; b < n; ++b)
              if (nodes[b] == c) {
                e(k, b) = 1.0;
                break;
              }
          }
        }
        Eigen::Matrix3d mt = Eigen::Matrix3d::Constant(1.0) + Eigen::Matrix3d::Identity();
        mt *= tf.area(t) / 12.0;
        mf.noalias() += e.transpose() * mt * e;
      }
      df = mf.rowwise().sum();
      Eigen::LLT<Eigen::MatrixXd> llt(mf);
      if (llt.info() != Eigen::Success || !(df.minCoeff() > 0.0)) continue;  // degenerate: no contribution
      minv = llt.solve(Eigen::MatrixXd::Identity(n, n));
      for (int a = 0; a < n; ++a) {
        dValues[std::size_t(target.faceOffsets[std::size_t(f)] + a)] = df(a);
        for (int b = 0; b < n; ++b)
          aValues[aOffset[std::size_t(f)] + std::size_t(a * n + b)] = df(a) * minv(a, b);
      }
    }
    const int perTri = 3 * level * (level + 1) / 2;
    for (int i = 0; i < nt_; ++i) {
      double rowSum = 0.0;
      bool unmapped = false;
      for (int s = nodeFaceStart[std::size_t(i)]; s < nodeFaceStart[std::size_t(i) + 1]; ++s) {
        const int f = nodeFaces[std::size_t(s)];
        const int n = target.faceSize(f);
        const int* nodes = target.face(f);
        const int a = int(std::find(nodes, nodes + n, i) - nodes);
        rowSum += dValues[std::size_t(target.faceOffsets[std::size_t(f)] + a)];
        const double* arow = &aValues[aOffset[std::size_t(f)] + std::size_t(a * n)];
        for (int t = faceTri[std::size_t(f)]; t < faceTri[std::size_t(f) + 1]; ++t)
          for (int e = t * perTri; e < (t + 1) * perTri; ++e) {
            const auto [q, w] = perTriangle[std::size_t(e)];
            if (srcTri[std::size_t(q)] < 0) {
              unmapped = true;
              continue;
            }
            // ψ_i(q) from the N_b there; a point on the face's edge may belong to the neighbour's triangle,
            // where only the edge's end nodes (shared by both faces) are non-zero.
            double psi = 0.0;
            const QuadPoint& p = qp[std::size_t(q)];
            tf.forEachWeight(p.triangle, p.bary, [&](int node, double nv) {
              const int b = int(std::find(nodes, nodes + n, node) - nodes);
              if (b < n) psi += arow[b] * nv;
            });
            addSource(accC, i, q, w * psi);
          }
      }
      finishRow(i, rowSum, unmapped);
    }
  }
  m_ = fromCsr(nt_, nt_, mOuter, mInner, mValues);
  c_ = fromCsr(nt_, ns_, cOuter, cInner, cValues);
  lumpedInv_ = lumped_.unaryExpr([](double d) { return d > 0.0 ? 1.0 / d : 0.0; });
  report_.assemblySeconds = secondsSince(t0);

  if (mass_ == MassMatrix::Consistent) {
    t0 = Clock::now();
    const Eigen::SparseMatrix<double, Eigen::ColMajor, int> mc = m_;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double, Eigen::ColMajor, int>, Eigen::Lower,
                          Eigen::AMDOrdering<int>>
        ldlt(mc);
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 0.0))
      throw InputError(fmt::format(
          "interface mesh '{}': its mass matrix is not positive definite (degenerate faces?)", target.name));
    perm_.resize(std::size_t(nt_));
    const auto& idx = ldlt.permutationP().indices();
    for (int i = 0; i < nt_; ++i) perm_[std::size_t(i)] = idx(i);
    const auto& l = ldlt.matrixL().nestedExpression();
    lp_.assign(1, 0);
    lp_.reserve(std::size_t(nt_) + 1);
    for (int j = 0; j < nt_; ++j) {
      for (Eigen::SparseMatrix<double, Eigen::ColMajor, int>::InnerIterator it(l, j); it; ++it)
        if (it.row() > j) {
          li_.push_back(int(it.row()));
          lx_.push_back(it.value());
        }
      lp_.push_back(int(li_.size()));
    }
    dinv_.resize(std::size_t(nt_));
    for (int i = 0; i < nt_; ++i) dinv_[std::size_t(i)] = 1.0 / ldlt.vectorD()(i);
    report_.factorSeconds = secondsSince(t0);
  }
  scratch_.assign(std::size_t(3 * nt_), 0.0);

  const bool coarserTarget = target.meanEdgeLength() >= kDefectRatio * source.meanEdgeLength();
  if (options.defectCorrection == ProjectionOptions::Defect::On ||
      (options.defectCorrection == ProjectionOptions::Defect::Auto && coarserTarget)) {
    // P back onto the source: dual (sparse, exact for linear fields like H), never corrected itself.
    ProjectionOptions back = options;
    back.mass = MassMatrix::Dual;
    back.quadratureLevel = kAutoQuadrature;
    back.defectCorrection = ProjectionOptions::Defect::Off;
    back_ = std::make_unique<L2Projection>(target, source, back);
    // A source node P cannot reach would feed H a value pulled towards 0: only correct with P complete.
    if (back_->report().allMapped() || options.defectCorrection == ProjectionOptions::Defect::On) {
      report_.defectCorrection = true;
      defectSource_.assign(std::size_t(3 * ns_), 0.0);
      defectTarget_.assign(std::size_t(3 * nt_), 0.0);
    } else {
      back_.reset();
    }
  }
  report_.setupSeconds = secondsSince(tSetup);
}

int autoQuadratureLevel(const InterfaceMesh& source, const InterfaceMesh& target) {
  const double hs = source.meanEdgeLength(), ht = target.meanEdgeLength();
  if (!(hs > 0.0) || !(ht > 0.0) || !std::isfinite(ht / hs)) return 1;
  return int(std::clamp(std::ceil(2.0 * ht / hs - 1e-9), 1.0, double(kMaxQuadratureLevel)));
}

template <int K>
void L2Projection::solveInPlace(double* z) const {
  const int n = nt_;
  const int* lp = lp_.data();
  const int* li = li_.data();
  const double* lx = lx_.data();
  for (int j = 0; j < n; ++j) {  // L y = b, column by column
    double x[K];
    for (int k = 0; k < K; ++k) x[k] = z[j * K + k];
    for (int p = lp[j]; p < lp[j + 1]; ++p)
      for (int k = 0; k < K; ++k) z[li[p] * K + k] -= lx[p] * x[k];
  }
  for (int j = n - 1; j >= 0; --j) {  // Lᵀ x = D⁻¹ y, with the diagonal scaling fused in
    double s[K];
    for (int k = 0; k < K; ++k) s[k] = z[j * K + k] * dinv_[std::size_t(j)];
    for (int p = lp[j]; p < lp[j + 1]; ++p)
      for (int k = 0; k < K; ++k) s[k] -= lx[p] * z[li[p] * K + k];
    for (int k = 0; k < K; ++k) z[j * K + k] = s[k];
  }
}

template <int K>
void L2Projection::applyK(const double* us, double* ut) const {
  const int* outer = c_.outerIndexPtr();
  const int* inner = c_.innerIndexPtr();
  const double* val = c_.valuePtr();
  if (mass_ != MassMatrix::Consistent) {
    for (int i = 0; i < nt_; ++i) {
      double s[K] = {};
      for (int p = outer[i]; p < outer[i + 1]; ++p)
        for (int k = 0; k < K; ++k) s[k] += val[p] * us[inner[p] * K + k];
      for (int k = 0; k < K; ++k) ut[i * K + k] = s[k] * lumpedInv_[i];
    }
    return;
  }
  double* z = scratch_.data();
  for (int i = 0; i < nt_; ++i) {  // z = P C u_s
    double s[K] = {};
    for (int p = outer[i]; p < outer[i + 1]; ++p)
      for (int k = 0; k < K; ++k) s[k] += val[p] * us[inner[p] * K + k];
    for (int k = 0; k < K; ++k) z[perm_[std::size_t(i)] * K + k] = s[k];
  }
  solveInPlace<K>(z);
  for (int i = 0; i < nt_; ++i)
    for (int k = 0; k < K; ++k) ut[i * K + k] = z[perm_[std::size_t(i)] * K + k];
}

template <int K>
void L2Projection::applyTransposeK(const double* ft, double* fs) const {
  const int* outer = c_.outerIndexPtr();
  const int* inner = c_.innerIndexPtr();
  const double* val = c_.valuePtr();
  std::fill(fs, fs + std::size_t(ns_) * K, 0.0);
  if (mass_ != MassMatrix::Consistent) {
    for (int i = 0; i < nt_; ++i) {
      double x[K];
      for (int k = 0; k < K; ++k) x[k] = ft[i * K + k] * lumpedInv_[i];
      for (int p = outer[i]; p < outer[i + 1]; ++p)
        for (int k = 0; k < K; ++k) fs[inner[p] * K + k] += val[p] * x[k];
    }
    return;
  }
  // Hᵀ f = Cᵀ M⁻¹ f (M symmetric).
  double* z = scratch_.data();
  for (int i = 0; i < nt_; ++i)
    for (int k = 0; k < K; ++k) z[perm_[std::size_t(i)] * K + k] = ft[i * K + k];
  solveInPlace<K>(z);
  for (int i = 0; i < nt_; ++i) {
    double x[K];
    for (int k = 0; k < K; ++k) x[k] = z[perm_[std::size_t(i)] * K + k];
    for (int p = outer[i]; p < outer[i + 1]; ++p)
      for (int k = 0; k < K; ++k) fs[inner[p] * K + k] += val[p] * x[k];
  }
}

namespace {
void checkComponents(int components) {
  if (components != 1 && components != 3)
    throw std::invalid_argument(fmt::format("L2Projection: {} components (1 or 3 supported)", components));
}
}  // namespace

void L2Projection::applyBase(const double* us, double* ut, int components) const {
  if (components == 1)
    applyK<1>(us, ut);
  else
    applyK<3>(us, ut);
}

void L2Projection::applyTransposeBase(const double* ft, double* fs, int components) const {
  if (components == 1)
    applyTransposeK<1>(ft, fs);
  else
    applyTransposeK<3>(ft, fs);
}

// The defect correction (ProjectionOptions::defectCorrection): H u carries the projection's averaging error
// e = H u − u_t (~c h_t² ∇²u); P maps the target field back to the source nearly exactly (the source is
// finer), so H P H u carries it twice, and 2 H u − H P H u = u_t + O(h_t⁴) + the source's own error. Both
// H and P reproduce constants and linear fields, so H' does, and Hᵀ' = 2Hᵀ − Hᵀ Pᵀ Hᵀ conserves force
// and moment exactly as Hᵀ does.
void L2Projection::apply(const double* us, double* ut, int components) const {
  checkComponents(components);
  applyBase(us, ut, components);
  if (!back_) return;
  back_->apply(ut, defectSource_.data(), components);
  applyBase(defectSource_.data(), defectTarget_.data(), components);
  const std::size_t n = std::size_t(nt_) * std::size_t(components);
  for (std::size_t i = 0; i < n; ++i) ut[i] = 2.0 * ut[i] - defectTarget_[i];
}

void L2Projection::applyTranspose(const double* ft, double* fs, int components) const {
  checkComponents(components);
  applyTransposeBase(ft, fs, components);
  if (!back_) return;
  back_->applyTranspose(fs, defectTarget_.data(), components);
  applyTransposeBase(defectTarget_.data(), defectSource_.data(), components);
  const std::size_t n = std::size_t(ns_) * std::size_t(components);
  for (std::size_t i = 0; i < n; ++i) fs[i] = 2.0 * fs[i] - defectSource_[i];
}

void L2Projection::apply(const Eigen::VectorXd& us, Eigen::VectorXd& ut, int components) const {
  checkComponents(components);
  if (us.size() != long(ns_) * components)
    throw std::invalid_argument(
        fmt::format("L2Projection::apply: {} source values, expected {}", us.size(), long(ns_) * components));
  ut.resize(long(nt_) * components);
  apply(us.data(), ut.data(), components);
}

void L2Projection::applyTranspose(const Eigen::VectorXd& ft, Eigen::VectorXd& fs, int components) const {
  checkComponents(components);
  if (ft.size() != long(nt_) * components)
    throw std::invalid_argument(fmt::format("L2Projection::applyTranspose: {} target values, expected {}",
                                            ft.size(), long(nt_) * components));
  fs.resize(long(ns_) * components);
  applyTranspose(ft.data(), fs.data(), components);
}

L2Projection::SparseRows L2Projection::operatorMatrix(double dropTolerance) const {
  if (back_) {  // the corrected operator, column by column
    std::vector<Eigen::Triplet<double, int>> entries;
    std::vector<double> e(std::size_t(ns_), 0.0);
    std::vector<double> col(std::size_t(nt_), 0.0);
    std::vector<double> rowMax(std::size_t(nt_), 0.0);
    for (int j = 0; j < ns_; ++j) {
      e[std::size_t(j)] = 1.0;
      apply(e.data(), col.data());
      e[std::size_t(j)] = 0.0;
      for (int i = 0; i < nt_; ++i)
        if (col[std::size_t(i)] != 0.0) {
          entries.emplace_back(i, j, col[std::size_t(i)]);
          rowMax[std::size_t(i)] = std::max(rowMax[std::size_t(i)], std::abs(col[std::size_t(i)]));
        }
    }
    entries.erase(std::remove_if(entries.begin(), entries.end(),
                                 [&](const auto& t) {
                                   return std::abs(t.value()) < dropTolerance * rowMax[std::size_t(t.row())];
                                 }),
                  entries.end());
    SparseRows h(nt_, ns_);
    h.setFromTriplets(entries.begin(), entries.end());
    return h;
  }
  if (mass_ != MassMatrix::Consistent) {
    SparseRows h = lumpedInv_.asDiagonal() * c_;
    return h;
  }
  // Column j of H = M⁻¹ (column j of C).
  const Eigen::SparseMatrix<double, Eigen::ColMajor, int> cc = c_;
  std::vector<Eigen::Triplet<double, int>> entries;
  std::vector<double> z(static_cast<std::size_t>(nt_));
  for (int j = 0; j < ns_; ++j) {
    std::fill(z.begin(), z.end(), 0.0);
    for (Eigen::SparseMatrix<double, Eigen::ColMajor, int>::InnerIterator it(cc, j); it; ++it)
      z[std::size_t(perm_[std::size_t(it.row())])] = it.value();
    solveInPlace<1>(z.data());
    for (int i = 0; i < nt_; ++i) {
      const double v = z[std::size_t(perm_[std::size_t(i)])];
      if (v != 0.0) entries.emplace_back(i, j, v);
    }
  }
  std::vector<double> rowMax(std::size_t(nt_), 0.0);
  for (const auto& e : entries)
    rowMax[std::size_t(e.row())] = std::max(rowMax[std::size_t(e.row())], std::abs(e.value()));
  entries.erase(std::remove_if(entries.begin(), entries.end(),
                               [&](const auto& e) {
                                 return std::abs(e.value()) < dropTolerance * rowMax[std::size_t(e.row())];
                               }),
                entries.end());
  SparseRows h(nt_, ns_);
  h.setFromTriplets(entries.begin(), entries.end());
  return h;
}

}  // namespace fsi::coupling
