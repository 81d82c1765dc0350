// The registry of element kinds: one line per kind. The order is the order of every loop over kinds (lumped
// and scaled mass sums, stiffness bounds, output fields, diagnosis); new kinds go at the end so existing
// results keep their round-off.
#include "structure/elements/BarElement.hpp"
#include "structure/elements/CableElement.hpp"
#include "structure/elements/ElementKind.hpp"
#include "structure/elements/MembraneElement.hpp"
#include "structure/elements/PointMassElement.hpp"

namespace fsi::structure {

const std::vector<const ElementKind*>& elementKinds() {
  static const MembraneKind membrane;
  static const CableKind cable;
  static const PointMassKind pointMass;
  static const BarKind bar;
  static const std::vector<const ElementKind*> kinds{&membrane, &cable, &pointMass, &bar};
  return kinds;
}

const ElementKind* findElementKind(const std::string& name) {
  for (const ElementKind* k : elementKinds())
    if (k->name() == name) return k;
  return nullptr;
}

}  // namespace fsi::structure
