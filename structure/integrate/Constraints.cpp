#include "structure/integrate/Constraints.hpp"

namespace fsi::structure {

void Constraints::applyTo(Nodes& nodes) const {
  for (int d : fixedDofs) {
    nodes.invMassDof[d] = 0.0;
    nodes.v[d] = 0.0;
  }
  for (const auto& p : prescribed) nodes.invMassDof[3 * p.node + p.component] = 0.0;
}

}  // namespace fsi::structure
