#include "coupling/effects/CouplingEffects.hpp"

namespace fsi::coupling {

void registerCouplingEffects() {
  structure::registerEffectKind(pressureFieldEffect());
}

}  // namespace fsi::coupling
