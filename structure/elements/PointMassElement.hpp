#pragma once
// The point mass as an element kind: a lumped mass on one node (a payload), stored in model.pointMasses. It
// has no internal force, no stiffness and no wave speed, so it adds no force effect, does not bound the
// stable step and is never mass-scaled; its only contribution is its mass, which is physical mass (gravity
// acts on it, body drag and probes see it).

#include "structure/elements/ElementKind.hpp"

namespace fsi::structure {

class PointMassKind final : public ElementKind {
 public:
  std::string name() const override { return "point_mass"; }
  int count(const Model& model) const override { return model.pointMasses.count; }
  /// "point mass 1 of mesh 'wing'".
  std::string describe(const Model& model, int element) const override;
  /// None: a point mass resists nothing but acceleration.
  std::unique_ptr<Effect> makeForces(const Model& model, const ElementDamping& damping) const override;
  void addLumpedMass(const Model& model, std::vector<double>& mass) const override;
  double referenceStableDt(const Model& model) const override;
  ScaledMass scaleMass(Model& model, double need) const override;
  void addStiffnessBounds(const Model& model, const double* x, std::vector<double>& dofRow,
                          std::vector<double>& dofDiag) const override;
};

}  // namespace fsi::structure
