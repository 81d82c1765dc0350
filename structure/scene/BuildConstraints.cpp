#include "structure/scene/BuildConstraints.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "structure/scene/ExtrudeTies.hpp"
#include "structure/scene/ReadTimeFunction.hpp"
#include "structure/scene/SceneSchema.hpp"

namespace fsi::structure {

const SchemaSection& fixSchema() {
  static const SchemaSection s{"constraints[i] (fix)",
                               "hold displacement components of nodes at zero",
                               {{"nodes", KeyType::Selector, "", "", "required", {}, {}, {}, "the nodes"},
                                {"fix",
                                 KeyType::Strings,
                                 "",
                                 "",
                                 "required",
                                 {},
                                 {},
                                 {"x", "y", "z", "all"},
                                 "the components held: x, y, z or all, or a list of them"}}};
  return s;
}

const SchemaSection& symmetrySchema() {
  static const SchemaSection s{
      "constraints[i].symmetry",
      "every node within tolerance of the plane: an axis normal fixes that component, an oblique one slides",
      {{"point", KeyType::Vec3, "m", "[0, 0, 0]", "", {}, {}, {}, "a point of the plane"},
       {"normal", KeyType::Vec3, "-", "", "required", {}, {}, {}, "the plane's normal (non-zero)"},
       {"tolerance",
        KeyType::Number,
        "m",
        "1e-9",
        "",
        {},
        {},
        {},
        "distance from the plane that counts as on it"}}};
  return s;
}

const SchemaSection& prescribeSchema() {
  static const SchemaSection s{
      "constraints[i].prescribe",
      "drive the nodes to X + a f(t) along a component or a direction (with `nodes` beside it)",
      {{"component",
        KeyType::Choice,
        "",
        "",
        "this or direction",
        {},
        {},
        {"x", "y", "z"},
        "the coordinate driven"},
       {"direction",
        KeyType::Vec3,
        "-",
        "",
        "this or component",
        {},
        {},
        {},
        "drive the whole position along this line (finite, non-zero)"},
       {"amplitude", KeyType::Number, "m", "", "required", {}, {}, {}, "a"},
       {"function",
        KeyType::Any,
        "",
        "",
        "constant 1",
        {},
        {},
        {},
        "f(t) (docs/SCENES.md, Time functions)"}}};
  return s;
}

Constraints buildConstraints(const YamlMap& top, const Model& model, const SetResolver& sets) {
  Constraints constraints;
  const std::string& fileName = top.file();
  // Who constrained what, for the checks of the tie groups (formed after the whole list is read, so that
  // the order of the entries does not matter).
  const int nodeCount = model.nodes.count;
  ConstraintOrigins origins{std::vector<int>(3 * std::size_t(nodeCount), -1),
                            std::vector<int>(std::size_t(nodeCount), -1),
                            std::vector<int>(std::size_t(nodeCount), -1)};
  std::vector<ExtrudeRequest> extrusions;
  if (top.has("constraints")) {
    const YAML::Node list = top.raw("constraints");
    if (!list.IsSequence()) top.failAt("constraints", "expected a list");
    for (std::size_t i = 0; i < list.size(); ++i) {
      YamlMap c(list[i], fileName, fmt::format("constraints[{}]", i));
      if (c.has("fix")) {
        const SchemaMap f(c, fixSchema());
        const auto nodes = sets.nodes(c.required("nodes"), c.childPath("nodes"));
        for (const auto& comp : c.strings("fix")) {
          const std::vector<std::string>& valid = f.section().key("fix").choices;
          if (std::find(valid.begin(), valid.end(), comp) == valid.end())
            c.failAt("fix", fmt::format("'{}' is not a component; valid: x, y, z, all", comp));
          for (int n : nodes)
            for (int k = 0; k < 3; ++k)
              if (comp == "all" || comp == valid[k]) {
                constraints.fixedDofs.push_back(3 * n + k);
                origins.fixedBy[3 * n + k] = int(i);
              }
        }
        f.finish();
      } else if (c.has("symmetry")) {
        YamlMap sMap = c.map("symmetry");
        const SchemaMap s(sMap, symmetrySchema());
        const auto pt = s.vec3("point");
        auto n = s.vec3("normal");
        const double tol = s.number("tolerance");
        s.finish();
        const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!(len > 0)) sMap.failAt("normal", "must not be zero");
        for (auto& v : n) v /= len;
        int axis = -1;
        for (int k = 0; k < 3; ++k)
          if (std::abs(std::abs(n[k]) - 1.0) < 1e-14) axis = k;
        int count = 0;
        const Nodes& N = model.nodes;
        for (int j = 0; j < N.count; ++j) {
          double d = 0;
          for (int k = 0; k < 3; ++k) d += (N.X[3 * j + k] - pt[k]) * n[k];
          if (std::abs(d) > tol) continue;
          ++count;
          if (axis >= 0) {
            constraints.fixedDofs.push_back(3 * j + axis);
            origins.fixedBy[3 * j + axis] = int(i);
          } else {
            constraints.sliders.push_back({j, n});
            origins.sliderBy[j] = int(i);
          }
        }
        if (count == 0) c.failAt("symmetry", "no node lies on this plane (check point, normal, tolerance)");
        c.finish({"symmetry"});
      } else if (c.has("prescribe")) {
        const auto nodes = sets.nodes(c.required("nodes"), c.childPath("nodes"));
        YamlMap p = c.map("prescribe");
        const SchemaMap ps(p, prescribeSchema());
        const double amp = ps.number("amplitude");
        const TimeFunction fn = readTimeFunction(p, "function");
        // A direction d prescribes the whole displacement a·f(t)·d/|d|: one component motion per axis (those
        // with d_k = 0 are held), so the node follows the line exactly and the integrators' per-component
        // handling (zero inverse mass, impulse and work accounting) carries over unchanged.
        const bool byDirection = p.has("direction"), byComponent = p.has("component");
        if (byDirection && byComponent) p.fail("give either 'component' or 'direction', not both");
        std::array<double, 3> along{0, 0, 0};
        if (byDirection) {
          along = p.vec3("direction");
          const double len = std::sqrt(along[0] * along[0] + along[1] * along[1] + along[2] * along[2]);
          if (!(len > 0) || !std::isfinite(len)) p.failAt("direction", "must be a finite, non-zero vector");
          for (double& d : along) d /= len;
        } else if (byComponent) {
          const std::string componentName = ps.string("component");
          along[componentName == "x" ? 0 : componentName == "y" ? 1 : 2] = 1.0;
        }
        ps.finish();  // a misspelt key first
        if (!byDirection && !byComponent)
          p.fail("give either 'component: x|y|z' or 'direction: [dx, dy, dz]'");
        for (int n : nodes) {
          origins.prescribedBy[n] = int(i);
          for (int k = 0; k < 3; ++k)
            if (byDirection || along[k] != 0) constraints.prescribed.push_back({n, k, amp * along[k], fn});
        }
        c.finish({"nodes", "prescribe"});
      } else if (c.has("extrude")) {
        extrusions.push_back(readExtrude(c, int(i), sets.nodes(c.required("nodes"), c.childPath("nodes"))));
      } else {
        c.fail(
            "a constraint needs one of: fix (with nodes), symmetry, prescribe (with nodes), extrude (with "
            "nodes)");
      }
    }
    addExtrudeTies(extrusions, model, origins, constraints);
    auto& f = constraints.fixedDofs;
    std::sort(f.begin(), f.end());
    f.erase(std::unique(f.begin(), f.end()), f.end());
  }
  return constraints;
}

}  // namespace fsi::structure
