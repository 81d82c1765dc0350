#pragma once
// The membrane triangle as an element kind: constant-strain corotational triangles with the (wrinkling) St
// Venant–Kirchhoff law, stored in model.membranes. Forces and the stable step are MembraneForces' templated
// kernel; kinematics and law are MembraneKinematics.hpp; this file adds mass, mass scaling, the relaxation
// stiffness bounds, output fields and diagnosis.

#include "structure/elements/ElementKind.hpp"

namespace fsi::structure {

class MembraneKind final : public ElementKind {
 public:
  std::string name() const override { return "membrane"; }
  int count(const Model& model) const override { return model.membranes.count; }
  std::string describe(const Model& model, int element) const override {
    return model.describeTriangle(element);
  }
  /// `material: NAME`, a membrane material.
  std::vector<std::string> meshKeys() const override { return {"material"}; }
  void readMeshKeys(const YamlMap& entry, const MaterialTable& materials, MeshInput& in) const override;
  void checkMeshInput(const YamlMap& entry, const MeshInput& in) const override;
  std::unique_ptr<Effect> makeForces(const Model& model, const ElementDamping& damping) const override;
  void addLumpedMass(const Model& model, std::vector<double>& mass) const override;
  double referenceStableDt(const Model& model) const override;
  ScaledMass scaleMass(Model& model, double need) const override;
  void addStiffnessBounds(const Model& model, const double* x, std::vector<double>& dofRow,
                          std::vector<double>& dofDiag) const override;
  void addStressBoundMass(const Model& model, const double* x, double lambda, std::vector<double>& m,
                          std::vector<char>& covered) const override;
  std::vector<std::string> outputFields() const override {
    return {"stress", "principal_stress", "wrinkle_state"};
  }
  void addFields(const Model& model, const double* x, const std::set<std::string>& wanted,
                 ElementFieldBuffers& buffers, std::vector<FieldView>& views) const override;
  std::optional<StrainedElement> mostStrained(const Model& model, const double* x) const override;
};

}  // namespace fsi::structure
