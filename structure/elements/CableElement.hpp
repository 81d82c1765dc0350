#pragma once
// The cable as an element kind: tension-only two-node cables stored in model.cables. Forces and the stable
// step are CableForces' templated kernel; this file adds mass, mass scaling, the relaxation stiffness bounds
// and the cable_force output field.

#include "structure/elements/ElementKind.hpp"

namespace fsi::structure {

class CableKind final : public ElementKind {
 public:
  std::string name() const override { return "cable"; }
  int count(const Model& model) const override { return model.cables.count; }
  std::string describe(const Model& model, int element) const override {
    return model.describeCable(element);
  }
  /// `cable_material: NAME`, a cable material.
  std::vector<std::string> meshKeys() const override { return {"cable_material", "cables", "edge_cables"}; }
  void readMeshKeys(const YamlMap& entry, const MaterialTable& materials, MeshInput& in) const override;
  void checkMeshInput(const YamlMap& entry, const MeshInput& in) const override;
  std::unique_ptr<Effect> makeForces(const Model& model, const ElementDamping& damping) const override;
  void addLumpedMass(const Model& model, std::vector<double>& mass) const override;
  double referenceStableDt(const Model& model) const override;
  std::optional<LimitingElement> limitingElementAt(const Model& model, int node) const override;
  ScaledMass scaleMass(Model& model, double need) const override;
  void addStiffnessBounds(const Model& model, const double* x, std::vector<double>& dofRow,
                          std::vector<double>& dofDiag) const override;
  std::vector<std::string> outputFields() const override { return {"cable_force"}; }
  void addFields(const Model& model, const double* x, const std::set<std::string>& wanted,
                 ElementFieldBuffers& buffers, std::vector<FieldView>& views) const override;
};

}  // namespace fsi::structure
