#pragma once
// What went wrong when the explicit integration became unstable: the first non-finite node, or the
// fastest node when the energy balance failed, the most strained membrane element, the step used against
// the element estimate, and the last stable state. Shared by structure-only runs (Simulation) and the
// structural side of coupled runs (coupling::StructureParticipant).
#include <string>

#include "structure/integrate/CentralDifference.hpp"
#include "structure/scene/Scene.hpp"

namespace fsi::structure {

/// One-paragraph diagnosis of the current (unstable) state of `cd`; `goodSteps`/`goodTime` name the last
/// stable state the caller kept. `nonFinite`: the integrator reported a non-finite state.
std::string diagnoseInstability(const Scene& scene, const CentralDifference& cd, long goodSteps,
                                double goodTime, bool nonFinite);

}  // namespace fsi::structure
