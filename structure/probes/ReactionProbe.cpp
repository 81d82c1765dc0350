// reaction and applied_load: a component of the summed reaction force (internal minus external force, what
// the supports exert) or of the summed external force (pressure, drag, gravity, nodal loads) on a set of
// nodes. Together they check global equilibrium: at a static state the reactions of all supports plus the
// applied load on all nodes vanish (equilibrium_error does it in one number).
#include "structure/probes/ProbeKinds.hpp"

namespace fsi::structure {

namespace {

// Σ over the nodes of f_int − f_ext (the reaction; tie forces left out, ProbeState::reactions) or of f_ext
// (the applied load), as the probe's component.
template <bool Reaction>
void evaluate(const ProbeSpec& p, ProbeState& state, std::vector<double>& vals) {
  const Nodes& N = state.model().nodes;
  const double* reaction = Reaction ? state.reactions().data() : nullptr;
  double r[3] = {0, 0, 0};
  for (int n : p.nodes)
    for (int k = 0; k < 3; ++k) r[k] += Reaction ? reaction[3 * n + k] : N.fext[3 * n + k];
  vals.push_back(vectorComponent(r, p.component));
}

}  // namespace

ProbeKind reactionProbe() {
  return {"reaction", "a component of the reaction force summed over a set of nodes", evaluate<true>};
}

ProbeKind appliedLoadProbe() {
  return {"applied_load", "a component of the external (applied) force summed over a set of nodes",
          evaluate<false>};
}

}  // namespace fsi::structure
