#include "structure/elements/PointMassElement.hpp"

#include <fmt/format.h>

#include <limits>

namespace fsi::structure {

std::string PointMassKind::describe(const Model& model, int element) const {
  const PointMasses& P = model.pointMasses;
  return fmt::format("point mass {} of mesh '{}'", P.tag[element], model.meshes[P.mesh[element]].name);
}

std::unique_ptr<Effect> PointMassKind::makeForces(const Model& /*model*/,
                                                  const ElementDamping& /*damping*/) const {
  return nullptr;
}

void PointMassKind::addLumpedMass(const Model& model, std::vector<double>& mass) const {
  const PointMasses& P = model.pointMasses;
  for (int e = 0; e < P.count; ++e) mass[P.node[e]] += P.mass[e];
}

// A rigid lump has no wave to resolve: the step is bounded by the elements the node belongs to (their
// bound only grows with the added mass).
double PointMassKind::referenceStableDt(const Model& /*model*/) const {
  return std::numeric_limits<double>::infinity();
}

ScaledMass PointMassKind::scaleMass(Model& /*model*/, double /*need*/) const {
  return {};
}

// No stiffness: nothing to add to the Gerschgorin bounds.
void PointMassKind::addStiffnessBounds(const Model& /*model*/, const double* /*x*/,
                                       std::vector<double>& /*dofRow*/,
                                       std::vector<double>& /*dofDiag*/) const {}

}  // namespace fsi::structure
