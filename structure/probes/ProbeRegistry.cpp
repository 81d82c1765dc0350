#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "structure/probes/ProbeKinds.hpp"

namespace fsi::structure {

// The entries, one per probe file. Register a new probe here: its function below and in the table.
ProbeKind displacementProbe();
ProbeKind positionProbe();
ProbeKind reactionProbe();
ProbeKind volumeProbe();
ProbeKind stressProbe();
ProbeKind lineTensionProbe();     // LineTensionProbe.cpp
ProbeKind reactionMomentProbe();  // ReactionMomentProbe.cpp
ProbeKind pitchAngleProbe();      // PitchAngleProbe.cpp
ProbeKind appliedLoadProbe();     // ReactionProbe.cpp
ProbeKind equilibriumProbe();     // EquilibriumProbe.cpp
ProbeKind laplaceProbe();         // LaplaceProbe.cpp
ProbeKind foldsProbe();           // FoldsProbe.cpp

const std::vector<ProbeKind>& probeKinds() {
  static const std::vector<ProbeKind> kinds{displacementProbe(),   positionProbe(),   reactionProbe(),
                                            volumeProbe(),         stressProbe(),     lineTensionProbe(),
                                            reactionMomentProbe(), pitchAngleProbe(), appliedLoadProbe(),
                                            equilibriumProbe(),    laplaceProbe(),    foldsProbe()};
  return kinds;
}

const MembraneStressField& ProbeState::membraneStress() {
  if (!haveStress_) membraneStresses(scene_.model->membranes, scene_.model->nodes.x.data(), stress_);
  haveStress_ = true;
  return stress_;
}

const std::vector<double>& ProbeState::reactions() {
  if (!haveReactions_) scene_.constraints.reactions(scene_.model->nodes, reactions_);
  haveReactions_ = true;
  return reactions_;
}

ProbeComponent readComponent(const YamlMap& entry, const std::vector<std::string>& allowed) {
  static const std::vector<std::pair<std::string, ProbeComponent>> names{
      {"x", ProbeComponent::X},
      {"y", ProbeComponent::Y},
      {"z", ProbeComponent::Z},
      {"magnitude", ProbeComponent::Magnitude},
      {"radial", ProbeComponent::Radial}};
  const std::string c = entry.choice("component", allowed);
  for (const auto& [name, value] : names)
    if (name == c) return value;
  entry.failAt("component", fmt::format("'{}' is not a component", c));  // unreachable: `allowed` is checked
}

ProbeReduce readReduce(const YamlMap& entry, const std::vector<std::string>& allowed,
                       const std::string& fallback) {
  static const std::vector<std::pair<std::string, ProbeReduce>> names{{"value", ProbeReduce::Value},
                                                                      {"mean", ProbeReduce::Mean},
                                                                      {"max", ProbeReduce::Max},
                                                                      {"min", ProbeReduce::Min},
                                                                      {"sum", ProbeReduce::Sum}};
  const std::string r = entry.choice("reduce", allowed, fallback);
  for (const auto& [name, value] : names)
    if (name == r) return value;
  entry.failAt("reduce", fmt::format("'{}' is not a reduction", r));  // unreachable: `allowed` is checked
}

double vectorComponent(const double* v, ProbeComponent c) {
  switch (c) {
    case ProbeComponent::X:
      return v[0];
    case ProbeComponent::Y:
      return v[1];
    case ProbeComponent::Z:
      return v[2];
    case ProbeComponent::Magnitude:
    case ProbeComponent::Radial:
      break;
  }
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

std::vector<ProbeSpec> readProbes(const YamlMap& top, const SetResolver& sets) {
  std::vector<ProbeSpec> probes;
  if (!top.has("probes")) return probes;
  std::vector<std::string> types;
  for (const ProbeKind& k : probeKinds()) types.push_back(k.name);
  YamlMap ps = top.map("probes");
  for (const auto& name : ps.keys()) {
    // The name becomes a column of /tables/probes in results.h5 (next to 'time') and a key of summary.json.
    if (name.empty() || name == "." || name == "time" || name.find('/') != std::string::npos ||
        std::any_of(name.begin(), name.end(), [](char ch) { return (ch >= 0 && ch < 0x20) || ch == 0x7F; }))
      ps.failAt(name, fmt::format("'{}' cannot name a probe: it must be non-empty, not 'time' or '.', and "
                                  "without '/' or control characters",
                                  name));
    YamlMap p = ps.map(name);
    ProbeSpec spec;
    spec.name = name;
    const std::string type = p.choice("type", types);
    for (const ProbeKind& k : probeKinds())
      if (k.name == type) spec.kind = &k;
    spec.kind->parse(p, sets, spec);
    probes.push_back(std::move(spec));
  }
  return probes;
}

}  // namespace fsi::structure
