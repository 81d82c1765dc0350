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
  std::string label() const override { return "membrane triangles"; }
  int count(const Model& model) const override { return model.membranes.count; }
  std::string describe(const Model& model, int element) const override {
    return model.describeTriangle(element);
  }
  /// model.membranes from every mesh's triangles (MeshInput::membraneMaterial), sorted by material then by
  /// first node: the reference geometry in the element's edge frame, the wave speed and the reference step.
  void build(const std::vector<MeshInput>& inputs, const MaterialTable& materials,
             Model& model) const override;
  std::unique_ptr<Effect> makeForces(const Model& model, const ElementDamping& damping) const override;
  void addLumpedMass(const Model& model, std::vector<double>& mass) const override;
  double referenceStableDt(const Model& model) const override;
  ScaledMass scaleMass(Model& model, double need) const override;
  void addStiffnessBounds(const Model& model, const double* x, std::vector<double>& dofRow,
                          std::vector<double>& dofDiag) const override;
  void addStressBoundMass(const Model& model, const double* x, double lambda, std::vector<double>& m,
                          std::vector<char>& covered) const override;
  /// "membranes": Triangle cells in /mesh/triangles (written even when empty: the file layout's).
  std::optional<CellSet> outputCells(const Model& model) const override;
  std::vector<std::string> outputFields() const override {
    return {"stress", "principal_stress", "wrinkle_state"};
  }
  void addFields(const Model& model, const double* x, const std::set<std::string>& wanted,
                 ElementFieldBuffers& buffers, std::vector<FieldView>& views) const override;
  /// max_principal_stress [Pa] (the largest major principal Cauchy stress).
  std::vector<std::pair<std::string, double>> report(const Model& model, const double* x) const override;
  std::optional<StrainedElement> mostStrained(const Model& model, const double* x) const override;
};

}  // namespace fsi::structure
