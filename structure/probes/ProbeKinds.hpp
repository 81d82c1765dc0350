#pragma once
// The registry of probe kinds: what each probe computes. Every kind is one entry {name, description,
// evaluate} over a ProbeSpec (its nodes, triangles, lines and options, resolved at load time). How a scene
// spells a probe (its keys, their checks, the sets they resolve) is the scene's: a reader per kind in
// structure/scene/probes/, registered there under the same name. Adding a probe = one file here with its
// evaluate function + one registration in ProbeRegistry.cpp, and its reader + one line in
// scene/probes/ReadProbes.cpp (docs/ARCHITECTURE.md, "How to add a probe"). Probes are evaluated at output
// times only, never in the step loop.

#include <string>
#include <vector>

#include "structure/elements/MembraneForces.hpp"
#include "structure/integrate/Constraints.hpp"
#include "structure/model/Model.hpp"
#include "structure/probes/ProbeSpec.hpp"

namespace fsi::structure {

/// What a probe's evaluate function may read: the model's current state, the membrane stresses and the
/// nodes' reactions (each computed once per evaluation, on first use).
class ProbeState {
 public:
  ProbeState(const Model& model, const Constraints& constraints) : model_(model), constraints_(constraints) {}
  const Model& model() const { return model_; }
  const MembraneStressField& membraneStress();
  /// The reaction f_int − f_ext of every node (3 per node), tie forces left out (Constraints::reactions):
  /// what the supports exert, plus −m·a on moving nodes. Computed once per evaluation, on first use.
  const std::vector<double>& reactions();

 private:
  const Model& model_;
  const Constraints& constraints_;
  MembraneStressField stress_;
  bool haveStress_ = false;
  std::vector<double> reactions_;
  bool haveReactions_ = false;
};

struct ProbeKind {
  std::string name;         ///< the probe's `type:`
  std::string description;  ///< one line, for docs and messages
  /// Appends the probe's values (one per node/triangle, or one in all) for its reduction.
  void (*evaluate)(const ProbeSpec& spec, ProbeState& state, std::vector<double>& values) = nullptr;
};

/// Every probe kind, in the order their names are listed in messages.
const std::vector<ProbeKind>& probeKinds();

/// The kind named `name`, or nullptr.
const ProbeKind* findProbeKind(const std::string& name);

/// The x, y or z component or the magnitude of a vector (Radial is the caller's: it needs a centre).
double vectorComponent(const double* v, ProbeComponent c);

}  // namespace fsi::structure
