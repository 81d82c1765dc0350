#pragma once
// A mapped nodal field against the exact field at the target mesh's nodes: the largest and the RMS error,
// each relative to the exact field's range over those nodes (1 if it is constant). Shared by the mapping
// tests.

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <vector>

#include "coupling/interface/InterfaceMesh.hpp"

namespace fsi::coupling::testing {

struct NodalError {
  double max = 0.0, rms = 0.0;
};

inline NodalError nodalError(const InterfaceMesh& m, const std::vector<double>& u,
                             const std::function<double(const std::array<double, 3>&)>& f) {
  double lo = HUGE_VAL, hi = -HUGE_VAL, mx = 0.0, s2 = 0.0;
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const double e = f(m.points[i]);
    lo = std::min(lo, e);
    hi = std::max(hi, e);
    mx = std::max(mx, std::abs(u[i] - e));
    s2 += (u[i] - e) * (u[i] - e);
  }
  const double range = hi > lo ? hi - lo : 1.0;
  return {mx / range, std::sqrt(s2 / double(m.points.size())) / range};
}

}  // namespace fsi::coupling::testing
