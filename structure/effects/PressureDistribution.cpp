#include "structure/effects/PressureDistribution.hpp"

#include "structure/effects/TriangleLoad.hpp"

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
