// reaction and applied_load: a component of the summed reaction force (internal minus external force, what
// the supports exert) or of the summed external force (pressure, drag, gravity, nodal loads) on a set of
// nodes. Together they check global equilibrium: at a static state the reactions of all supports plus the
// applied load on all nodes vanish (equilibrium_error does it in one number).
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

// Σ over the nodes of f_int − f_ext (the reaction; tie forces left out, ProbeState::reactions) or of f_ext
// (the applied load), as the probe's component.
template <bool Reaction>
void evaluate(const ProbeSpec& p, ProbeState& state, std::vector<double>& vals) {
  const Nodes& N = state.scene().model->nodes;
  const double* reaction = Reaction ? state.reactions().data() : nullptr;
  double r[3] = {0, 0, 0};
  for (int n : p.nodes)
    for (int k = 0; k < 3; ++k) r[k] += Reaction ? reaction[3 * n + k] : N.fext[3 * n + k];
  vals.push_back(vectorComponent(r, p.component));
}

}  // namespace

ProbeKind reactionProbe() {
  return {"reaction", kKeys, "a component of the reaction force summed over a set of nodes", parse,
          evaluate<true>};
}

ProbeKind appliedLoadProbe() {
  return {"applied_load", kKeys, "a component of the external (applied) force summed over a set of nodes",
          parse, evaluate<false>};
}

}  // namespace fsi::structure
