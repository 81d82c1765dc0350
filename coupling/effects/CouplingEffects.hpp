#pragma once
// The scene effects that need the coupling library, registered into the structure's effect registry
// (structure/scene/effects/EffectKinds.hpp, registerEffectKind): the structure library cannot include
// coupling headers (structure <- coupling <- adapter/apps), so these kinds are added from above. Every
// program that loads scenes calls registerCouplingEffects() once at start-up, before loading any (`fsi`, the
// OpenFOAM adapter, the unit tests that use them); a second call does nothing.
//   pressure_field  an external pressure (or Cp) field from another code's solution, mapped onto triangles
//                   (PressureFieldEffect.cpp; docs/PARAFOIL.md "One-way FSI from a CFD solution")

#include "structure/scene/effects/EffectKinds.hpp"

namespace fsi::coupling {

structure::EffectKind pressureFieldEffect();

/// Registers every coupling-side effect kind (idempotent).
void registerCouplingEffects();

}  // namespace fsi::coupling
