#pragma once
// What went wrong when a run became unstable: for the explicit integration the first non-finite node, or the
// energy growth / balance with the fastest node, the most strained membrane element, the step used against
// the element estimate, and the last stable state; for dynamic relaxation the residual history, the node with
// the largest residual, its fictitious mass and the most strained element. Shared by structure-only runs
// (Simulation) and the structural side of coupled runs (coupling::StructureParticipant).
#include <string>

#include "structure/integrate/CentralDifference.hpp"
#include "structure/integrate/DynamicRelaxation.hpp"
#include "structure/scene/Scene.hpp"

namespace fsi::structure {

/// One-paragraph diagnosis of the current (unstable) state of `cd`; `goodSteps`/`goodTime` name the last
/// stable state the caller kept. `nonFinite`: the integrator reported a non-finite state; otherwise (or if no
/// node is non-finite) the energy ledger says what failed: growth() above kGrowthLimit, the energy created in
/// the elements (at the last monitoring step, or `created` if >= 0: the check at the current state), or the
/// balance.
std::string diagnoseInstability(const Scene& scene, const CentralDifference& cd, long goodSteps,
                                double goodTime, bool nonFinite, double created = -1);

/// Diagnosis of a diverged (or not converged) dynamic-relaxation run, at the model's current state (forces as
/// last evaluated by `dr`).
std::string diagnoseRelaxation(const Scene& scene, const DynamicRelaxation& dr, const RelaxationResult& r);

}  // namespace fsi::structure
