#pragma once
// The nodal forces of a uniform pressure on one triangle, on its CURRENT area and normal: every node receives
// p A n / 3 = p (d21 × d31) / 6. Shared by the pressure loads (FollowerPressure, PressureDistribution).

namespace fsi::structure {

/// Adds the forces of pressure p on triangle n[0..2] (positions x, 3 per node) to f; `p6` is p / 6.
inline void addTrianglePressure(const double* __restrict x, const int* n, double p6, double* __restrict f) {
  const double* p1 = x + 3 * n[0];
  const double* p2 = x + 3 * n[1];
  const double* p3 = x + 3 * n[2];
  const double a[3] = {p2[0] - p1[0], p2[1] - p1[1], p2[2] - p1[2]};
  const double b[3] = {p3[0] - p1[0], p3[1] - p1[1], p3[2] - p1[2]};
  const double c[3] = {p6 * (a[1] * b[2] - a[2] * b[1]), p6 * (a[2] * b[0] - a[0] * b[2]),
                       p6 * (a[0] * b[1] - a[1] * b[0])};
  for (int k = 0; k < 3; ++k) {
    f[3 * n[0] + k] += c[k];
    f[3 * n[1] + k] += c[k];
    f[3 * n[2] + k] += c[k];
  }
}

}  // namespace fsi::structure
