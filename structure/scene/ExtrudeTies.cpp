#include "structure/scene/ExtrudeTies.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace fsi::structure {

namespace {

const char* const kAxis[3] = {"x", "y", "z"};

double dot(const std::array<double, 3>& a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// Distance across d between the reference positions of nodes i and j.
double across(const Nodes& N, const std::array<double, 3>& d, int i, int j) {
  double r[3];
  for (int k = 0; k < 3; ++k) r[k] = N.X[3 * j + k] - N.X[3 * i + k];
  const double along = dot(d, r);
  double s = 0;
  for (int k = 0; k < 3; ++k) s += (r[k] - along * d[k]) * (r[k] - along * d[k]);
  return std::sqrt(s);
}

std::string at(const Nodes& N, int i) {
  return fmt::format("({:.9g}, {:.9g}, {:.9g})", N.X[3 * i], N.X[3 * i + 1], N.X[3 * i + 2]);
}

int find(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

/// The groups of nodes whose reference positions lie within `tol` of each other across d (chains joined):
/// sorted by the first in-plane coordinate, each node is compared with those that follow it within tol.
std::vector<std::vector<int>> groupAcross(const Nodes& N, const std::vector<int>& nodes,
                                          const std::array<double, 3>& d, double tol) {
  // An in-plane unit vector e (any vector across d).
  const int least =
      int(std::min_element(d.begin(), d.end(), [](double a, double b) { return std::abs(a) < std::abs(b); }) -
          d.begin());
  std::array<double, 3> e{0, 0, 0};
  e[least] = 1.0;
  const double ed = e[least] * d[least];
  double len = 0;
  for (int k = 0; k < 3; ++k) {
    e[k] -= ed * d[k];
    len += e[k] * e[k];
  }
  for (double& c : e) c /= std::sqrt(len);
  const int n = int(nodes.size());
  std::vector<double> key(n);
  for (int a = 0; a < n; ++a) key[a] = dot(e, &N.X[3 * nodes[a]]);
  std::vector<int> order(n), parent(n);
  std::iota(order.begin(), order.end(), 0);
  std::iota(parent.begin(), parent.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n && key[order[b]] - key[order[a]] <= tol; ++b)
      if (across(N, d, nodes[order[a]], nodes[order[b]]) <= tol)
        parent[find(parent, order[a])] = find(parent, order[b]);
  std::vector<std::vector<int>> byRoot(n);
  for (int a = 0; a < n; ++a) byRoot[find(parent, a)].push_back(nodes[a]);  // nodes sorted: members sorted
  std::vector<std::vector<int>> groups;
  for (auto& g : byRoot)
    if (!g.empty()) groups.push_back(std::move(g));
  std::sort(groups.begin(), groups.end());
  return groups;
}

}  // namespace

const SchemaSection& extrudeSchema() {
  static const SchemaSection s{
      "constraints[i].extrude",
      "a 2D model: tie the nodes that coincide apart from their coordinate along a direction (with `nodes`)",
      {{"direction",
        KeyType::Vec3,
        "-",
        "",
        "required",
        {},
        {},
        {},
        "the extrusion direction (finite, non-zero, need not be unit)"},
       {"tolerance",
        KeyType::Number,
        "m",
        "1e-9",
        "",
        incl(0),
        {},
        {},
        "distance across the direction within which nodes form a tie group"},
       {"hold",
        KeyType::Boolean,
        "",
        "false",
        "",
        {},
        {},
        {},
        "also hold the displacement along the direction at zero (plane strain)"}}};
  return s;
}

ExtrudeRequest readExtrude(const YamlMap& entry, int index, std::vector<int> nodes) {
  YamlMap e = entry.map("extrude");
  ExtrudeRequest r{entry, e, index, std::move(nodes)};
  r.direction = e.vec3("direction");
  r.tolerance = e.number("tolerance", 1e-9);
  r.hold = e.boolean("hold", false);
  e.finish(extrudeSchema().names());
  entry.finish({"nodes", "extrude"});
  auto& d = r.direction;
  const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(len > 0) || !std::isfinite(len)) e.failAt("direction", "must be a finite, non-zero vector");
  for (double& c : d) c /= len;
  // An axis given with round-off becomes the axis exactly: the tied components are then plain dofs.
  for (int k = 0; k < 3; ++k)
    if (std::abs(std::abs(d[k]) - 1.0) < 1e-14) {
      d = {0, 0, 0};
      d[k] = 1.0;
    }
  if (!(r.tolerance >= 0)) e.failAt("tolerance", "must be >= 0 (a distance across the direction, in m)");
  return r;
}

void addExtrudeTies(const std::vector<ExtrudeRequest>& requests, const Model& model,
                    const ConstraintOrigins& origins, Constraints& c) {
  const Nodes& N = model.nodes;
  std::vector<int> tiedBy(N.count, -1);
  for (const ExtrudeRequest& r : requests) {
    const auto& d = r.direction;
    int axis = -1;
    for (int k = 0; k < 3; ++k)
      if (d[k] == 1.0) axis = k;
    const std::string dir = fmt::format("[{:.6g}, {:.6g}, {:.6g}]", d[0], d[1], d[2]);
    auto fail = [&](const std::string& message) { r.entry.failAt("extrude", message); };
    const auto groups = groupAcross(N, r.nodes, d, r.tolerance);
    if (std::none_of(groups.begin(), groups.end(), [](const auto& g) { return g.size() >= 2; }))
      fail(fmt::format(
          "the {} node(s) of this set form no tie group: no two of them lie within tolerance {} m "
          "of each other across the direction {} (check the set, the direction and the tolerance)",
          r.nodes.size(), r.tolerance, dir));
    for (const auto& g : groups) {
      if (g.size() < 2)
        fail(fmt::format(
            "{} at {} has no partner: no other node of the set lies within tolerance {} m of its "
            "line along the direction {}; every node of an extruded strip needs one on each other "
            "row (check the set, the direction and the tolerance)",
            model.describeNode(g[0]), at(N, g[0]), r.tolerance, dir));
      for (int i : g)
        if (across(N, d, g[0], i) > r.tolerance)
          fail(fmt::format(
              "{} at {} and {} at {} are joined through nodes between them but lie {:.3g} m apart "
              "across the direction, beyond tolerance {} m: they do not form one group",
              model.describeNode(g[0]), at(N, g[0]), model.describeNode(i), at(N, i), across(N, d, g[0], i),
              r.tolerance));
      for (int i : g) {
        if (tiedBy[i] >= 0)
          fail(fmt::format("{} is already tied by constraints[{}]; a node can be in one tie group only",
                           model.describeNode(i), tiedBy[i]));
        tiedBy[i] = r.index;
        if (origins.prescribedBy[i] >= 0)
          fail(fmt::format("{} has a prescribed motion (constraints[{}]); a tied node cannot have one",
                           model.describeNode(i), origins.prescribedBy[i]));
        if (origins.sliderBy[i] >= 0)
          for (const PlaneSlider& s : c.sliders)
            if (s.node == i && std::abs(dot(d, s.normal.data())) < 1.0 - 1e-12)
              fail(fmt::format(
                  "{} slides on the oblique symmetry plane of constraints[{}], whose normal is not "
                  "the direction {}: the group's motion across the direction would leave the plane",
                  model.describeNode(i), origins.sliderBy[i], dir));
      }
      // A component fixed on every node of the group is not tied (nothing moves: mask 0); one fixed on some
      // nodes only would hold the whole group through the tie, which is refused rather than guessed.
      std::array<double, 3> mask{1, 1, 1};
      const bool allFixed = std::all_of(g.begin(), g.end(), [&](int i) {
        return origins.fixedBy[3 * i] >= 0 && origins.fixedBy[3 * i + 1] >= 0 &&
               origins.fixedBy[3 * i + 2] >= 0;
      });
      if (allFixed) continue;  // e.g. a clamped end: no tie needed
      for (int k = 0; k < 3; ++k) {
        if (k == axis) {
          mask[k] = 0;  // along d: each node's own (t() removes it anyway)
          continue;
        }
        const auto fixed =
            std::find_if(g.begin(), g.end(), [&](int i) { return origins.fixedBy[3 * i + k] >= 0; });
        if (fixed == g.end()) continue;
        if (axis < 0 && d[k] != 0)
          fail(fmt::format(
              "{} is fixed in {} (constraints[{}]), a component with a part along the oblique "
              "direction {}: a tie group across an oblique direction may only be fixed whole (all its "
              "nodes in x, y and z) or in a component across the direction",
              model.describeNode(*fixed), kAxis[k], origins.fixedBy[3 * *fixed + k], dir));
        const auto loose =
            std::find_if(g.begin(), g.end(), [&](int i) { return origins.fixedBy[3 * i + k] < 0; });
        if (loose != g.end())
          fail(fmt::format(
              "{} is fixed in {} (constraints[{}]) but {} of its tie group is not: the group moves "
              "as one across the direction, so fix all its nodes in {} or none",
              model.describeNode(*fixed), kAxis[k], origins.fixedBy[3 * *fixed + k],
              model.describeNode(*loose), kAxis[k]));
        mask[k] = 0;
      }
      if (mask[0] != 0 || mask[1] != 0 || mask[2] != 0) c.ties.add(g, d, mask);
    }
    // hold: no displacement along the direction (plane strain), as a symmetry plane with d as its normal.
    if (r.hold)
      for (int i : r.nodes) {
        if (axis >= 0)
          c.fixedDofs.push_back(3 * i + axis);
        else
          c.sliders.push_back({i, d});
      }
  }
}

}  // namespace fsi::structure
