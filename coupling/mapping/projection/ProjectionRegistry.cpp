#include "coupling/mapping/projection/ProjectionRegistry.hpp"

#include <stdexcept>
#include <string>

#include "coupling/mapping/projection/ConsistentProjection.hpp"
#include "coupling/mapping/projection/DualProjection.hpp"
#include "coupling/mapping/projection/LumpedProjection.hpp"

namespace fsi::coupling {

const std::vector<ProjectionVariantEntry>& projectionVariants() {
  // One line per variant. Explicit rather than self-registering objects: a static library drops an object
  // file nothing refers to, and with it its registration.
  static const std::vector<ProjectionVariantEntry> entries{
      {MassMatrix::Consistent, false, makeConsistentProjection},
      {MassMatrix::Lumped, false, makeLumpedProjection},
      {MassMatrix::Dual, true, makeDualProjection},
  };
  return entries;
}

const ProjectionVariantEntry& projectionVariant(MassMatrix mass) {
  for (const ProjectionVariantEntry& e : projectionVariants())
    if (e.mass == mass) return e;
  throw std::logic_error(std::string("L2Projection: no variant '") + toString(mass) + "' registered");
}

}  // namespace fsi::coupling
