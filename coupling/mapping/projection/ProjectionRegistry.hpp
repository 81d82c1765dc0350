#pragma once
// The registry of the L2 projection's variants (coupling/mapping/projection/, one class per file): one entry
// per MassMatrix value a projection can be (Auto resolves to one of them first, resolveMass), with its
// factory. Adding a variant: a value of MassMatrix (and its name, L2Projection.hpp), its class, one line in
// projectionVariants().

#include <memory>
#include <vector>

#include "coupling/mapping/projection/ProjectionVariant.hpp"

namespace fsi::coupling {

struct ProjectionVariantEntry {
  MassMatrix mass;
  /// Whether its assembly reads every fan triangle's own quadrature points (ProjectionSetup::perTriangle).
  bool perTriangleQuadrature;
  std::unique_ptr<ProjectionVariant> (*make)(const ProjectionSetup&, ProjectionReport&);
};

/// Every registered variant.
const std::vector<ProjectionVariantEntry>& projectionVariants();
/// The entry of `mass` (never Auto); throws std::logic_error for one not registered.
const ProjectionVariantEntry& projectionVariant(MassMatrix mass);

}  // namespace fsi::coupling
