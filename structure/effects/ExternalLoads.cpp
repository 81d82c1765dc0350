#include "structure/effects/ExternalLoads.hpp"

#include "structure/effects/TriangleLoad.hpp"

namespace fsi::structure {

FollowerPressure::FollowerPressure(std::string label, std::vector<int> triangleConn, double value,
                                   TimeFunction f)
    : label_(std::move(label)), conn_(std::move(triangleConn)), value_(value), fn_(std::move(f)) {}

void FollowerPressure::addRange(ForceContext& ctx, int begin, int end) const {
  const double p6 = ctx.loadFactor * valueAt(ctx.time) / 6.0;  // p A n / 3 = p (d21 x d31) / 6
  if (p6 == 0.0) return;
  const double* __restrict x = ctx.x;
  double* __restrict f = ctx.fext;
  for (int e = begin; e < end; ++e) {
    const int* n = &conn_[3 * e];
    addTrianglePressure(x, n, p6, f);
  }
}

Gravity::Gravity(const std::vector<double>& physicalMass, std::array<double, 3> g, TimeFunction f)
    : weight_(3 * physicalMass.size()), fn_(std::move(f)) {
  for (std::size_t i = 0; i < physicalMass.size(); ++i)
    for (int k = 0; k < 3; ++k) weight_[3 * i + k] = physicalMass[i] * g[k];
}

Connectivity Gravity::connectivity() const {
  Connectivity c;
  c.items = int(weight_.size() / 3);
  c.light = true;
  return c;
}

void Gravity::addRange(ForceContext& ctx, int begin, int end) const {
  const double s = ctx.loadFactor * fn_(ctx.time);
  double* __restrict f = ctx.fext;
  for (std::size_t i = 3 * std::size_t(begin), n = 3 * std::size_t(end); i < n; ++i) f[i] += s * weight_[i];
}

NodalForces::NodalForces(std::string label, std::vector<int> nodes, std::array<double, 3> force,
                         TimeFunction f)
    : label_(std::move(label)), nodes_(std::move(nodes)), force_(force), fn_(std::move(f)) {}

void NodalForces::addForces(ForceContext& ctx) const {
  const double s = ctx.loadFactor * fn_(ctx.time);
  for (int n : nodes_)
    for (int k = 0; k < 3; ++k) ctx.fext[3 * n + k] += s * force_[k];
}

}  // namespace fsi::structure
