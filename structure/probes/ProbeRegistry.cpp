#include <cmath>

#include "structure/probes/ProbeKinds.hpp"

namespace fsi::structure {

// The entries, one per probe file. Register a new probe here: its function below and in the table.
ProbeKind displacementProbe();
ProbeKind positionProbe();
ProbeKind reactionProbe();
ProbeKind volumeProbe();
ProbeKind stressProbe();
ProbeKind lineTensionProbe();        // LineTensionProbe.cpp
ProbeKind reactionMomentProbe();     // ReactionMomentProbe.cpp
ProbeKind pitchAngleProbe();         // PitchAngleProbe.cpp
ProbeKind appliedLoadProbe();        // ReactionProbe.cpp
ProbeKind equilibriumProbe();        // EquilibriumProbe.cpp
ProbeKind laplaceProbe();            // LaplaceProbe.cpp
ProbeKind foldsProbe();              // FoldsProbe.cpp
ProbeKind projectedDiameterProbe();  // ProjectedDiameterProbe.cpp

const std::vector<ProbeKind>& probeKinds() {
  static const std::vector<ProbeKind> kinds{displacementProbe(),     positionProbe(),   reactionProbe(),
                                            volumeProbe(),           stressProbe(),     lineTensionProbe(),
                                            reactionMomentProbe(),   pitchAngleProbe(), appliedLoadProbe(),
                                            equilibriumProbe(),      laplaceProbe(),    foldsProbe(),
                                            projectedDiameterProbe()};
  return kinds;
}

const ProbeKind* findProbeKind(const std::string& name) {
  for (const ProbeKind& k : probeKinds())
    if (k.name == name) return &k;
  return nullptr;
}

const MembraneStressField& ProbeState::membraneStress() {
  if (!haveStress_) membraneStresses(model_.membranes, model_.nodes.x.data(), stress_);
  haveStress_ = true;
  return stress_;
}

const std::vector<double>& ProbeState::reactions() {
  if (!haveReactions_) constraints_.reactions(model_.nodes, reactions_);
  haveReactions_ = true;
  return reactions_;
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

}  // namespace fsi::structure
