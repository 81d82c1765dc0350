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
