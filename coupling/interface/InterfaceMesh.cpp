#include "coupling/interface/InterfaceMesh.hpp"

#include <cmath>

namespace fsi::coupling {

std::array<double, 3> InterfaceMesh::faceCentroid(int f) const {
  std::array<double, 3> c{0.0, 0.0, 0.0};
  const int n = faceSize(f);
  const int* nodes = face(f);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) c[k] += points[nodes[i]][k];
  for (int k = 0; k < 3; ++k) c[k] /= n;
  return c;
}

double InterfaceMesh::faceArea(int f) const {
  const std::array<double, 3> c = faceCentroid(f);
  const int n = faceSize(f);
  const int* v = face(f);
  double area = 0;
  for (int k = 0; k < n; ++k) {
    const auto& a = points[std::size_t(v[k])];
    const auto& b = points[std::size_t(v[(k + 1) % n])];
    const double u[3] = {a[0] - c[0], a[1] - c[1], a[2] - c[2]};
    const double w[3] = {b[0] - c[0], b[1] - c[1], b[2] - c[2]};
    const double x = u[1] * w[2] - u[2] * w[1], y = u[2] * w[0] - u[0] * w[2], z = u[0] * w[1] - u[1] * w[0];
    area += 0.5 * std::sqrt(x * x + y * y + z * z);
  }
  return area;
}

std::vector<double> InterfaceMesh::pointAreas() const {
  std::vector<double> area(points.size(), 0.0);
  for (int f = 0; f < numFaces(); ++f) {
    const double share = faceArea(f) / faceSize(f);
    const int* v = face(f);
    for (int k = 0; k < faceSize(f); ++k) area[std::size_t(v[k])] += share;
  }
  return area;
}

double InterfaceMesh::meanEdgeLength() const {
  double sum = 0.0;
  long count = 0;
  for (int f = 0; f < numFaces(); ++f) {
    const int n = faceSize(f);
    const int* nodes = face(f);
    for (int i = 0; i < n; ++i) {
      const auto& a = points[nodes[i]];
      const auto& b = points[nodes[(i + 1) % n]];
      sum += std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                       (a[2] - b[2]) * (a[2] - b[2]));
      ++count;
    }
  }
  return count > 0 ? sum / double(count) : 0.0;
}

}  // namespace fsi::coupling
