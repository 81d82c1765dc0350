#include "coupling/mapping/projection/SourcePoints.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace fsi::coupling {

namespace {

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

SourcePoints findSourcePoints(const SurfaceSearch& search, const FanTriangulation& tf,
                              const std::vector<QuadPoint>& qp, bool keepGap, bool keepSide,
                              ProjectionReport& report) {
  const long nq = long(qp.size());
  // Closest source point of every quadrature point; consecutive points are neighbours, so the previous
  // answer is a tight initial bound for the next search.
  SourcePoints sp;
  std::vector<int>& srcTri = sp.triangle;
  std::vector<std::array<double, 3>>& srcBary = sp.bary;
  std::vector<std::array<double, 3>>& gap = sp.gap;
  srcTri.assign(std::size_t(nq), -1);
  srcBary.resize(static_cast<std::size_t>(nq));
  gap.resize(keepGap ? std::size_t(nq) : 0);  // x − P(x)
  int hint = -1;
  for (long q = 0; q < nq; ++q) {
    const std::array<double, 3> x = tf.position(qp[std::size_t(q)].triangle, qp[std::size_t(q)].bary);
    const SurfacePoint p = search.closest(x, hint);
    hint = p.triangle;
    if (p.mapped) {
      srcTri[std::size_t(q)] = p.triangle;
      srcBary[std::size_t(q)] = p.bary;
      if (keepGap) gap[std::size_t(q)] = {x[0] - p.point[0], x[1] - p.point[1], x[2] - p.point[2]};
      report.maxGap = std::max(report.maxGap, p.distance);
    } else {
      if (report.firstUnmappedPoints.size() < ProjectionReport::kListed)
        report.firstUnmappedPoints.push_back({q, x, p.distance});
      ++report.unmappedQuadraturePoints;
    }
  }
  if (keepSide) keepSides(search, tf, qp, srcTri, srcBary, gap, report);
  return sp;
}

}  // namespace fsi::coupling
