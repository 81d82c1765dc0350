#pragma once
// The cable as an element kind: tension-only two-node cables stored in model.cables. Forces and the stable
// step are CableForces' templated kernel; this file adds the build of model.cables (from every mesh's lines
// that no other kind claimed), mass, mass scaling, the relaxation stiffness bounds and the cable_force
// output field.

#include "structure/elements/ElementKind.hpp"

namespace fsi::structure {

class CableKind final : public ElementKind {
 public:
  std::string name() const override { return "cable"; }
  std::string label() const override { return "cables"; }
  int count(const Model& model) const override { return model.cables.count; }
  std::string describe(const Model& model, int element) const override {
    return model.describeCable(element);
  }
  /// model.cables from every mesh's lines (MeshInput::cableMaterial), sorted by material then by first node:
  /// rest lengths (a generator's slack ones) and wave speeds.
  void build(const std::vector<MeshInput>& inputs, const MaterialTable& materials,
             Model& model) const override;
  std::unique_ptr<Effect> makeForces(const Model& model, const ElementDamping& damping) const override;
  void addLumpedMass(const Model& model, std::vector<double>& mass) const override;
  double referenceStableDt(const Model& model) const override;
  std::optional<LimitingElement> limitingElementAt(const Model& model, int node) const override;
  ScaledMass scaleMass(Model& model, double need) const override;
  void addStiffnessBounds(const Model& model, const double* x, std::vector<double>& dofRow,
                          std::vector<double>& dofDiag) const override;
  /// "cables": Polyline cells in /mesh/lines (written even when empty: the file layout's).
  std::optional<CellSet> outputCells(const Model& model) const override;
  std::vector<std::string> outputFields() const override { return {"cable_force"}; }
  void addFields(const Model& model, const double* x, const std::set<std::string>& wanted,
                 ElementFieldBuffers& buffers, std::vector<FieldView>& views) const override;
  /// max_force [N] (the largest elastic tension).
  std::vector<std::pair<std::string, double>> report(const Model& model, const double* x) const override;
};

}  // namespace fsi::structure
