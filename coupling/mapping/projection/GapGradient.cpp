#include "coupling/mapping/projection/GapGradient.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace fsi::coupling {

GapGradient::GapGradient(const InterfaceMesh& mesh, const FanTriangulation& fan, double minRadius)
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

void GapGradient::buildOne(int t) {
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
      reach = std::max(reach, (Eigen::Vector3d(mesh_.points[std::size_t(patch_[a])].data()) - centre).norm());
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

}  // namespace fsi::coupling
