// reaction_moment: a component of the moment about a point of the reaction forces (internal minus external
// force) on a set of nodes, Σ (x_i − about) × r_i at the current positions — e.g. the moment the anchored
// confluence point takes, whose change shows what a brake input does. `about` is a point [x, y, z] or a set
// of one node (e.g. wing/confluence: the moments about the anchor), taken at its reference position.
#include "structure/probes/ProbeKinds.hpp"

namespace fsi::structure {

namespace {

const std::vector<std::string> kKeys{"type", "nodes", "about", "component"};

void parse(const YamlMap& p, const SetResolver& sets, ProbeSpec& spec) {
  spec.reduce = ProbeReduce::Sum;
  spec.nodes = sets.nodes(p.required("nodes"), p.childPath("nodes"));
  const YAML::Node about = p.raw("about");
  if (about && about.IsScalar()) {
    // A node set: its one node's reference position (the anchor is held, so reference = current).
    const std::vector<int> one = sets.nodes(about, p.childPath("about"));
    if (one.size() != 1)
      p.failAt("about", "'" + about.as<std::string>() + "' has " + std::to_string(one.size()) +
                            " nodes; the moment's point is one node or [x, y, z]");
    const Nodes& N = sets.model().nodes;
    for (int k = 0; k < 3; ++k) spec.center[k] = N.X[3 * one[0] + k];
  } else {
    spec.center = p.vec3("about", {0, 0, 0});
  }
  spec.component = readComponent(p, {"x", "y", "z", "magnitude"});
  p.finish(kKeys);
}

void evaluate(const ProbeSpec& p, ProbeState& state, std::vector<double>& vals) {
  const Nodes& N = state.scene().model->nodes;
  const std::vector<double>& reaction = state.reactions();  // tie forces left out
  double m[3] = {0, 0, 0};
  for (int n : p.nodes) {
    double d[3], r[3];
    for (int k = 0; k < 3; ++k) {
      d[k] = N.x[3 * n + k] - p.center[k];
      r[k] = reaction[3 * n + k];
    }
    m[0] += d[1] * r[2] - d[2] * r[1];
    m[1] += d[2] * r[0] - d[0] * r[2];
    m[2] += d[0] * r[1] - d[1] * r[0];
  }
  vals.push_back(vectorComponent(m, p.component));
}

}  // namespace

ProbeKind reactionMomentProbe() {
  return {"reaction_moment", kKeys,
          "a component of the moment of the reaction forces of a set of nodes [N m]", parse, evaluate};
}

}  // namespace fsi::structure
