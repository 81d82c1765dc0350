#include "structure/effects/PressureDistribution.hpp"

#include <algorithm>
#include <cmath>

#include "structure/effects/TriangleLoad.hpp"

namespace fsi::structure {

PressureDistribution::PressureDistribution(std::string label, std::vector<int> triangleConn,
                                           std::vector<double> values, TimeFunction f)
    : label_(std::move(label)), conn_(std::move(triangleConn)), sixth_(std::move(values)), fn_(std::move(f)) {
  for (double& p : sixth_) p /= 6.0;
}

PressureDistribution PressureDistribution::dead(std::string label, std::vector<int> triangleConn,
                                                std::vector<double> values, TimeFunction f,
                                                const std::vector<double>& X) {
  PressureDistribution d(std::move(label), std::move(triangleConn), std::move(values), std::move(f));
  d.dead_.assign(3 * d.sixth_.size(), 0.0);
  std::vector<double> scratch(X.size(), 0.0);
  for (std::size_t e = 0; e < d.sixth_.size(); ++e) {
    // The force each node of the triangle receives at the reference state (read off node 0's sum).
    const int* n = &d.conn_[3 * e];
    double before[3];
    for (int k = 0; k < 3; ++k) before[k] = scratch[3 * n[0] + k];
    addTrianglePressure(X.data(), n, d.sixth_[e], scratch.data());
    for (int k = 0; k < 3; ++k) d.dead_[3 * e + k] = scratch[3 * n[0] + k] - before[k];
  }
  return d;
}

void PressureDistribution::addRange(ForceContext& ctx, int begin, int end) const {
  const double s = ctx.loadFactor * fn_(ctx.time);
  if (s == 0.0) return;
  if (!dead_.empty()) {
    double* __restrict f = ctx.fext;
    for (int e = begin; e < end; ++e)
      for (int a = 0; a < 3; ++a)
        for (int k = 0; k < 3; ++k) f[3 * conn_[3 * e + a] + k] += s * dead_[3 * e + k];
    return;
  }
  const double* __restrict x = ctx.x;
  double* __restrict f = ctx.fext;
  for (int e = begin; e < end; ++e) {
    const int* n = &conn_[3 * e];
    addTrianglePressure(x, n, s * sixth_[e], f);
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
