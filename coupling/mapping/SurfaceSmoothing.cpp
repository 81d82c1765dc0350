#include "coupling/mapping/SurfaceSmoothing.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

namespace fsi::coupling {

using P3 = std::array<double, 3>;

SurfaceSmoothing::SurfaceSmoothing(const InterfaceMesh& mesh, double length) : length_(length) {
  if (!(length > 0) || !std::isfinite(length))
    throw std::invalid_argument(fmt::format("SurfaceSmoothing: length {} (valid: > 0)", length));
  if (mesh.numFaces() == 0)
    throw std::invalid_argument("SurfaceSmoothing: the mesh '" + mesh.name + "' has no faces");
  const int n = mesh.numPoints();
  const std::vector<double> pointArea = mesh.pointAreas();  // M
  area_ = Eigen::Map<const Eigen::VectorXd>(pointArea.data(), n);
  std::map<std::pair<int, int>, double> weight;  // edge -> w_e
  for (int f = 0; f < mesh.numFaces(); ++f) {
    const double A = mesh.faceArea(f);
    const int nf = mesh.faceSize(f);
    if (!(A > 0))
      throw std::invalid_argument(fmt::format("SurfaceSmoothing: face {} of '{}' has no area", f, mesh.name));
    const int* v = mesh.face(f);
    for (int k = 0; k < nf; ++k) {
      const int a = v[k], b = v[(k + 1) % nf];
      const P3& pa = mesh.points[std::size_t(a)];
      const P3& pb = mesh.points[std::size_t(b)];
      const double l2 = (pa[0] - pb[0]) * (pa[0] - pb[0]) + (pa[1] - pb[1]) * (pa[1] - pb[1]) +
                        (pa[2] - pb[2]) * (pa[2] - pb[2]);
      if (!(l2 > 0))
        throw std::invalid_argument(
            fmt::format("SurfaceSmoothing: face {} of '{}' has an edge of zero length", f, mesh.name));
      weight[{std::min(a, b), std::max(a, b)}] += 2 * A / (nf * l2);
    }
  }
  // M + ℓ² K
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(4 * weight.size() + std::size_t(n));
  const double l2 = length * length;
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, area_[i]);
  for (const auto& [e, w] : weight) {
    t.emplace_back(e.first, e.first, l2 * w);
    t.emplace_back(e.second, e.second, l2 * w);
    t.emplace_back(e.first, e.second, -l2 * w);
    t.emplace_back(e.second, e.first, -l2 * w);
  }
  // A point on no face has no area: it keeps its own value (a unit row).
  for (int i = 0; i < n; ++i)
    if (area_[i] == 0) {
      area_[i] = 1;
      t.emplace_back(i, i, 1.0);
    }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  solver_.compute(A);
  if (solver_.info() != Eigen::Success)
    throw std::runtime_error("SurfaceSmoothing: the factorisation of M + l^2 K failed on '" + mesh.name +
                             "'");
  rhs_.resize(n);
  sol_.resize(n);
}

void SurfaceSmoothing::apply(const double* in, double* out, int components) const {
  const int n = points();
  for (int c = 0; c < components; ++c) {
    for (int i = 0; i < n; ++i)
      rhs_[i] = area_[i] * in[std::size_t(i) * std::size_t(components) + std::size_t(c)];
    sol_ = solver_.solve(rhs_);
    for (int i = 0; i < n; ++i) out[std::size_t(i) * std::size_t(components) + std::size_t(c)] = sol_[i];
  }
}

void SurfaceSmoothing::applyTranspose(const double* in, double* out, int components) const {
  const int n = points();
  for (int c = 0; c < components; ++c) {
    for (int i = 0; i < n; ++i) rhs_[i] = in[std::size_t(i) * std::size_t(components) + std::size_t(c)];
    sol_ = solver_.solve(rhs_);
    for (int i = 0; i < n; ++i)
      out[std::size_t(i) * std::size_t(components) + std::size_t(c)] = area_[i] * sol_[i];
  }
}

}  // namespace fsi::coupling
