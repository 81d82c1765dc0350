#include "coupling/mapping/MomentConservation.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace fsi::coupling {

MomentConservation::MomentConservation(std::vector<double> weights) : weights_(std::move(weights)) {
  double sum = 0;
  for (std::size_t i = 0; i < weights_.size(); ++i) {
    if (!(weights_[i] >= 0) || !std::isfinite(weights_[i]))
      throw std::invalid_argument(
          fmt::format("MomentConservation: weight {} of point {} (valid: finite, >= 0)", weights_[i], i));
    sum += weights_[i];
  }
  if (!(sum > 0))
    throw std::invalid_argument("MomentConservation: the weights sum to zero (no points, or none weighed)");
}

MomentConservation MomentConservation::onSurface(const InterfaceMesh& mesh) {
  if (mesh.numFaces() == 0) return MomentConservation(std::vector<double>(mesh.points.size(), 1.0));
  return MomentConservation(mesh.pointAreas());
}

MomentCorrection MomentConservation::apply(const double* x, double* loads,
                                           const std::array<double, 3>& targetMoment) const {
  const std::size_t n = weights_.size();
  // The moment the loads carry, and the weighted centroid.
  Eigen::Vector3d moment = Eigen::Vector3d::Zero(), c = Eigen::Vector3d::Zero();
  double wsum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d xi(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
    moment += xi.cross(Eigen::Vector3d(loads[3 * i], loads[3 * i + 1], loads[3 * i + 2]));
    c += weights_[i] * xi;
    wsum += weights_[i];
  }
  c /= wsum;
  const Eigen::Vector3d defect = Eigen::Vector3d(targetMoment[0], targetMoment[1], targetMoment[2]) - moment;
  // J = Σ w (|r|² I − r rᵀ)
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d r = Eigen::Vector3d(x[3 * i], x[3 * i + 1], x[3 * i + 2]) - c;
    J += weights_[i] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  // a = J⁺ ΔM: directions of J below 1e-12 of its largest eigenvalue (points on one line: the line's own
  // axis) carry nothing.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(J);
  const Eigen::Vector3d lambda = eig.eigenvalues();
  const double cut = 1e-12 * std::max(lambda.cwiseAbs().maxCoeff(), 0.0);
  Eigen::Vector3d a = Eigen::Vector3d::Zero(), remaining = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d v = eig.eigenvectors().col(k);
    const double m = v.dot(defect);
    if (lambda[k] > cut && lambda[k] > 0)
      a += (m / lambda[k]) * v;
    else
      remaining += m * v;
  }
  MomentCorrection out;
  for (int k = 0; k < 3; ++k) {
    out.defect[std::size_t(k)] = defect[k];
    out.remaining[std::size_t(k)] = remaining[k];
  }
  double largest2 = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d r = Eigen::Vector3d(x[3 * i], x[3 * i + 1], x[3 * i + 2]) - c;
    const Eigen::Vector3d d = weights_[i] * a.cross(r);
    for (int k = 0; k < 3; ++k) loads[3 * i + std::size_t(k)] += d[k];
    largest2 = std::max(largest2, d.squaredNorm());
  }
  out.largestNodalForce = std::sqrt(largest2);
  return out;
}

}  // namespace fsi::coupling
