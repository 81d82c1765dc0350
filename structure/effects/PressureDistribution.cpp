#include "structure/effects/PressureDistribution.hpp"

#include <algorithm>
#include <cmath>

namespace fsi::structure {

PressureDistribution::PressureDistribution(std::string label, std::vector<int> triangleConn,
                                           std::vector<double> values, TimeFunction f)
    : label_(std::move(label)), conn_(std::move(triangleConn)), sixth_(std::move(values)), fn_(std::move(f)) {
  for (double& p : sixth_) p /= 6.0;
}

void PressureDistribution::addForces(ForceContext& ctx) const {
  const double s = ctx.loadFactor * fn_(ctx.time);
  if (s == 0.0) return;
  const double* __restrict x = ctx.x;
  double* __restrict f = ctx.fext;
  const int ne = int(sixth_.size());
  for (int e = 0; e < ne; ++e) {
    const int* n = &conn_[3 * e];
    const double* p1 = x + 3 * n[0];
    const double* p2 = x + 3 * n[1];
    const double* p3 = x + 3 * n[2];
    const double a[3] = {p2[0] - p1[0], p2[1] - p1[1], p2[2] - p1[2]};
    const double b[3] = {p3[0] - p1[0], p3[1] - p1[1], p3[2] - p1[2]};
    const double p = s * sixth_[e];
    const double c[3] = {p * (a[1] * b[2] - a[2] * b[1]), p * (a[2] * b[0] - a[0] * b[2]),
                         p * (a[0] * b[1] - a[1] * b[0])};
    for (int k = 0; k < 3; ++k) {
      f[3 * n[0] + k] += c[k];
      f[3 * n[1] + k] += c[k];
      f[3 * n[2] + k] += c[k];
    }
  }
}

double CpTable::at(double x) const {
  if (xc.empty()) return 0.0;
  if (x <= xc.front()) return cp.front();
  if (x >= xc.back()) return cp.back();
  const std::size_t i = std::size_t(std::upper_bound(xc.begin(), xc.end(), x) - xc.begin());
  const double w = (x - xc[i - 1]) / (xc[i] - xc[i - 1]);
  return cp[i - 1] + w * (cp[i] - cp[i - 1]);
}

std::vector<double> chordwisePressure(const std::vector<double>& X, const std::vector<int>& conn,
                                      const CpTable& table, double q, std::array<double, 3> le,
                                      std::array<double, 3> axis, double chord) {
  const double len = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  std::vector<double> p(conn.size() / 3);
  for (std::size_t e = 0; e < p.size(); ++e) {
    double xc = 0;
    for (int k = 0; k < 3; ++k) {
      const double c =
          (X[3 * conn[3 * e] + k] + X[3 * conn[3 * e + 1] + k] + X[3 * conn[3 * e + 2] + k]) / 3.0;
      xc += (c - le[k]) * axis[k] / len;
    }
    p[e] = q * table.at(xc / chord);
  }
  return p;
}

}  // namespace fsi::structure
