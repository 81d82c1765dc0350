// displacement and position: a component of the displacement x - X or of the position x of nodes.
#include <fmt/format.h>

#include <cmath>

#include "structure/probes/ProbeKinds.hpp"

namespace fsi::structure {

namespace {

const std::vector<std::string> kKeys{"type", "nodes", "component", "center", "reduce"};

void parse(const YamlMap& p, const SetResolver& sets, ProbeSpec& spec) {
  spec.nodes = sets.nodes(p.required("nodes"), p.childPath("nodes"));
  spec.component = readComponent(p, {"x", "y", "z", "magnitude", "radial"});
  spec.center = p.vec3("center", {0, 0, 0});
  spec.reduce = readReduce(p, {"value", "mean", "max", "min"}, "value");
  if (spec.reduce == ProbeReduce::Value && spec.nodes.size() != 1)
    p.failAt("nodes", fmt::format("selects {} nodes; 'reduce: value' needs exactly one (use nearest, or "
                                  "reduce: mean | max | min)",
                                  spec.nodes.size()));
  p.finish(kKeys);
}

void displacement(const ProbeSpec& p, ProbeState& state, std::vector<double>& vals) {
  const Nodes& N = state.scene().model->nodes;
  for (int n : p.nodes) {
    const double u[3] = {N.x[3 * n] - N.X[3 * n], N.x[3 * n + 1] - N.X[3 * n + 1],
                         N.x[3 * n + 2] - N.X[3 * n + 2]};
    if (p.component == ProbeComponent::Radial) {
      double r = 0, r0 = 0;
      for (int k = 0; k < 3; ++k) {
        r += std::pow(N.x[3 * n + k] - p.center[k], 2);
        r0 += std::pow(N.X[3 * n + k] - p.center[k], 2);
      }
      vals.push_back(std::sqrt(r) - std::sqrt(r0));
    } else {
      vals.push_back(vectorComponent(u, p.component));
    }
  }
}

void position(const ProbeSpec& p, ProbeState& state, std::vector<double>& vals) {
  const Nodes& N = state.scene().model->nodes;
  const bool radial = p.component == ProbeComponent::Radial;
  for (int n : p.nodes) {
    double r[3];
    for (int k = 0; k < 3; ++k) r[k] = N.x[3 * n + k] - (radial ? p.center[k] : 0.0);
    vals.push_back(vectorComponent(r, p.component));  // radial: the magnitude of x - center
  }
}

}  // namespace

ProbeKind displacementProbe() {
  return {"displacement", kKeys, "a component of the displacement of a node (or reduced over nodes)", parse,
          displacement};
}

ProbeKind positionProbe() {
  return {"position", kKeys, "a component of the position of a node (or reduced over nodes)", parse,
          position};
}

}  // namespace fsi::structure
