#include "structure/effects/InterfacePressure.hpp"

#include <stdexcept>
#include <unordered_map>

namespace fsi::structure {

const char* toString(InterfaceLoadKind kind) {
  return kind == InterfaceLoadKind::Pressure ? "pressure (one value per interface node)"
                                             : "nodal forces (three values per interface node)";
}

namespace {
// The interface nodes [first, last) whose nodal forces triangles [begin, end) of `triangles` add; all of
// them for the whole range (also without triangles).
void nodeSlice(std::size_t nodes, int triangles, int begin, int end, std::size_t& first, std::size_t& last) {
  const auto at = [&](int e) {
    return e >= triangles ? nodes
                          : std::size_t((unsigned long long)(nodes) * unsigned(e) / unsigned(triangles));
  };
  first = begin <= 0 ? 0 : at(begin);
  last = at(end);
}
}  // namespace

InterfacePressure::InterfacePressure(std::vector<int> triangleConn, std::vector<int> nodes,
                                     const InterfaceLoad& load)
    : nodes_(std::move(nodes)), load_(load) {
  std::unordered_map<int, int> local;
  for (std::size_t i = 0; i < nodes_.size(); ++i) local[nodes_[i]] = int(i);
  conn_.reserve(triangleConn.size());
  for (int n : triangleConn) {
    const auto it = local.find(n);
    if (it == local.end())
      throw std::invalid_argument("interface triangle uses a node outside the interface");
    conn_.push_back(it->second);
  }
  const int nt = triangles();
  itemOffsets_.reserve(std::size_t(nt) + 1);
  itemOffsets_.push_back(0);
  for (int e = 0; e < nt; ++e) {
    for (int k = 0; k < 3; ++k) itemNodes_.push_back(nodes_[std::size_t(conn_[3 * std::size_t(e) + k])]);
    std::size_t first = 0, last = 0;
    nodeSlice(nodes_.size(), nt, e, e + 1, first, last);
    for (std::size_t i = first; i < last; ++i) itemNodes_.push_back(nodes_[i]);
    itemOffsets_.push_back(int(itemNodes_.size()));
  }
}

Connectivity InterfacePressure::connectivity() const {
  Connectivity c;
  c.items = triangles();
  c.nodes = itemNodes_.data();
  c.offsets = itemOffsets_.data();
  return c;
}

void InterfacePressure::addRange(ForceContext& ctx, const InterfaceLoad& load, int begin, int end) const {
  const std::size_t n = nodes_.size();
  // The owner sizes the load for its kind; a mismatch is a programming error, never a guess.
  if (load.values.size() != valuesPerInterface(load.kind, n))
    throw std::logic_error("interface load: " + std::to_string(load.values.size()) + " values for " +
                           toString(load.kind) + " on " + std::to_string(n) + " interface nodes");
  const double* __restrict q = load.values.data();
  const double lf = ctx.loadFactor;
  double* __restrict f = ctx.fext;
  if (load.kind == InterfaceLoadKind::NodalForces) {
    std::size_t first = 0, last = 0;
    nodeSlice(n, triangles(), begin, end, first, last);
    for (std::size_t i = first; i < last; ++i)
      for (int k = 0; k < 3; ++k) f[3 * nodes_[i] + k] += lf * q[3 * i + std::size_t(k)];
    return;
  }
  const double* __restrict x = ctx.x;
  for (int e = begin; e < end; ++e) {
    const int a = conn_[3 * e], b = conn_[3 * e + 1], c = conn_[3 * e + 2];
    const int na = nodes_[a], nb = nodes_[b], nc = nodes_[c];
    const double* p1 = x + 3 * na;
    const double* p2 = x + 3 * nb;
    const double* p3 = x + 3 * nc;
    const double u[3] = {p2[0] - p1[0], p2[1] - p1[1], p2[2] - p1[2]};
    const double v[3] = {p3[0] - p1[0], p3[1] - p1[1], p3[2] - p1[2]};
    // A n = (u x v)/2; node a gets (A n / 12)(2 p_a + p_b + p_c) = (u x v)(2 p_a + p_b + p_c)/24.
    const double An[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double pa = lf * q[a], pb = lf * q[b], pc = lf * q[c];
    const double sum = pa + pb + pc;
    const double wa = (sum + pa) / 24.0, wb = (sum + pb) / 24.0, wc = (sum + pc) / 24.0;
    for (int k = 0; k < 3; ++k) {
      f[3 * na + k] += wa * An[k];
      f[3 * nb + k] += wb * An[k];
      f[3 * nc + k] += wc * An[k];
    }
  }
}

}  // namespace fsi::structure
