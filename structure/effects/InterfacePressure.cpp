#include "structure/effects/InterfacePressure.hpp"

#include <algorithm>
#include <stdexcept>
#include <unordered_map>

namespace fsi::structure {

InterfacePressure::InterfacePressure(std::vector<int> triangleConn, std::vector<int> nodes)
    : nodes_(std::move(nodes)) {
  std::unordered_map<int, int> local;
  for (std::size_t i = 0; i < nodes_.size(); ++i) local[nodes_[i]] = int(i);
  conn_.reserve(triangleConn.size());
  for (int n : triangleConn) {
    const auto it = local.find(n);
    if (it == local.end())
      throw std::invalid_argument("interface triangle uses a node outside the interface");
    conn_.push_back(it->second);
  }
  p0_.assign(nodes_.size(), 0.0);
  p1_.assign(nodes_.size(), 0.0);
  p_.assign(nodes_.size(), 0.0);
}

void InterfacePressure::setWindow(double t0, double t1, const std::vector<double>& pStart,
                                  const std::vector<double>& pEnd, WindowLoad rule) {
  if (pStart.size() != nodes_.size() || pEnd.size() != nodes_.size())
    throw std::invalid_argument("interface pressure: one value per interface node expected");
  assign(t0, t1, pStart, pEnd, rule, false);
}

void InterfacePressure::setForceWindow(double t0, double t1, const std::vector<double>& fStart,
                                       const std::vector<double>& fEnd, WindowLoad rule) {
  if (fStart.size() != 3 * nodes_.size() || fEnd.size() != 3 * nodes_.size())
    throw std::invalid_argument("interface forces: three values per interface node expected");
  assign(t0, t1, fStart, fEnd, rule, true);
}

void InterfacePressure::assign(double t0, double t1, const std::vector<double>& start,
                               const std::vector<double>& end, WindowLoad rule, bool forces) {
  t0_ = t0;
  t1_ = t1;
  p0_ = start;
  p1_ = end;
  rule_ = rule;
  forces_ = forces;
}

double InterfacePressure::windowFraction(double time) const {
  return rule_ == WindowLoad::Mean                  ? 0.5
         : rule_ == WindowLoad::End || !(t1_ > t0_) ? 1.0
                                                    : std::clamp((time - t0_) / (t1_ - t0_), 0.0, 1.0);
}

void InterfacePressure::addForces(ForceContext& ctx) const {
  const double s = windowFraction(ctx.time);
  const std::size_t n = nodes_.size();
  if (forces_) {
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) {
        const std::size_t d = 3 * i + std::size_t(k);
        ctx.fext[3 * nodes_[i] + k] += ctx.loadFactor * (p0_[d] + s * (p1_[d] - p0_[d]));
      }
    return;
  }
  for (std::size_t i = 0; i < n; ++i) p_[i] = ctx.loadFactor * (p0_[i] + s * (p1_[i] - p0_[i]));
  const double* __restrict x = ctx.x;
  double* __restrict f = ctx.fext;
  const int ne = int(conn_.size() / 3);
  for (int e = 0; e < ne; ++e) {
    const int a = conn_[3 * e], b = conn_[3 * e + 1], c = conn_[3 * e + 2];
    const int na = nodes_[a], nb = nodes_[b], nc = nodes_[c];
    const double* p1 = x + 3 * na;
    const double* p2 = x + 3 * nb;
    const double* p3 = x + 3 * nc;
    const double u[3] = {p2[0] - p1[0], p2[1] - p1[1], p2[2] - p1[2]};
    const double v[3] = {p3[0] - p1[0], p3[1] - p1[1], p3[2] - p1[2]};
    // A n = (u x v)/2; node a gets (A n / 12)(2 p_a + p_b + p_c) = (u x v)(2 p_a + p_b + p_c)/24.
    const double An[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double sum = p_[a] + p_[b] + p_[c];
    const double wa = (sum + p_[a]) / 24.0, wb = (sum + p_[b]) / 24.0, wc = (sum + p_[c]) / 24.0;
    for (int k = 0; k < 3; ++k) {
      f[3 * na + k] += wa * An[k];
      f[3 * nb + k] += wb * An[k];
      f[3 * nc + k] += wc * An[k];
    }
  }
}

}  // namespace fsi::structure
