// applied_load: a component of the summed external force (pressure, drag, gravity, nodal loads) on a set of
// nodes; with the reaction of the supports it checks global equilibrium: at a static state the reactions of
// all supports plus the applied load on all nodes vanish.
#include "structure/probes/ProbeKinds.hpp"

namespace fsi::structure {

namespace {

const std::vector<std::string> kKeys{"type", "nodes", "component"};

void parse(const YamlMap& p, const SetResolver& sets, ProbeSpec& spec) {
  spec.reduce = ProbeReduce::Sum;
  spec.nodes = sets.nodes(p.required("nodes"), p.childPath("nodes"));
  spec.component = readComponent(p, {"x", "y", "z", "magnitude"});
  p.finish(kKeys);
}

void evaluate(const ProbeSpec& p, ProbeState& state, std::vector<double>& vals) {
  const Nodes& N = state.scene().model->nodes;
  double r[3] = {0, 0, 0};
  for (int n : p.nodes)
    for (int k = 0; k < 3; ++k) r[k] += N.fext[3 * n + k];
  vals.push_back(vectorComponent(r, p.component));
}

}  // namespace

ProbeKind appliedLoadProbe() {
  return {"applied_load", kKeys, "a component of the external (applied) force summed over a set of nodes",
          parse, evaluate};
}

}  // namespace fsi::structure
