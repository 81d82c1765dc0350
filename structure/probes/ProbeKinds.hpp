#pragma once
// The registry of probe kinds: every kind is one entry {name, keys, description, parse, evaluate}. The valid
// `type:` values of a probe (and their "did you mean") come from this table. Adding a probe = one file with
// its parse and evaluate functions + one registration in ProbeRegistry.cpp (docs/ARCHITECTURE.md, "How to add
// a probe"). Probes are evaluated at output times only, never in the step loop.

#include <map>
#include <string>
#include <vector>

#include "structure/elements/MembraneForces.hpp"
#include "structure/probes/ProbeSpec.hpp"
#include "structure/scene/Scene.hpp"
#include "structure/scene/SetResolver.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure {

/// What a probe's evaluate function may read: the scene's current state, the membrane stresses and the
/// nodes' reactions (each computed once per evaluation, on first use).
class ProbeState {
 public:
  explicit ProbeState(const Scene& scene) : scene_(scene) {}
  const Scene& scene() const { return scene_; }
  const MembraneStressField& membraneStress();
  /// The reaction f_int − f_ext of every node (3 per node), tie forces left out (Constraints::reactions):
  /// what the supports exert, plus −m·a on moving nodes. Computed once per evaluation, on first use.
  const std::vector<double>& reactions();

 private:
  const Scene& scene_;
  MembraneStressField stress_;
  bool haveStress_ = false;
  std::vector<double> reactions_;
  bool haveReactions_ = false;
};

struct ProbeKind {
  std::string name;               ///< the probe's `type:`
  std::vector<std::string> keys;  ///< the keys of its entry (with `type`)
  std::string description;        ///< one line, for docs and messages
  /// Reads the entry (calling entry.finish(keys)) into `spec`; selectors resolve through `sets`.
  void (*parse)(const YamlMap& entry, const SetResolver& sets, ProbeSpec& spec) = nullptr;
  /// Appends the probe's values (one per node/triangle, or one in all) for its reduction.
  void (*evaluate)(const ProbeSpec& spec, ProbeState& state, std::vector<double>& values) = nullptr;
};

/// Every probe kind, in the order their names are listed in messages.
const std::vector<ProbeKind>& probeKinds();

/// Reads the `probes:` section of the top-level map `top`.
std::vector<ProbeSpec> readProbes(const YamlMap& top, const SetResolver& sets);

/// `component:` of a probe entry, one of `allowed` (names x, y, z, magnitude, radial).
ProbeComponent readComponent(const YamlMap& entry, const std::vector<std::string>& allowed);

/// `reduce:` of a probe entry, one of `allowed` (names value, mean, max, min, sum).
ProbeReduce readReduce(const YamlMap& entry, const std::vector<std::string>& allowed,
                       const std::string& fallback);

/// The x, y or z component or the magnitude of a vector (Radial is the caller's: it needs a centre).
double vectorComponent(const double* v, ProbeComponent c);

}  // namespace fsi::structure
