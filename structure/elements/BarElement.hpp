#pragma once
// The bar as an element kind: a two-node linear elastic bar that carries tension and compression (a strut, a
// batten, a stiff tape), axial force N = EA (L − L0)/L0 plus the element damping (Rayleigh β and bulk
// viscosity b1, ElementDamping, as for cables). Its block (Bars, in model.kindBlocks) is built from the lines
// a mesh entry gives it (`bars:` and `bar_material:`, read by structure/scene/kinds/BarKeys.cpp into a
// BarInput); forces and the stable step are BarForces' templated kernel. Fields: bar_force [N] (tension
// positive) and bar_strain [-] on the "bars" cells of the results file.

#include <array>
#include <string>
#include <vector>

#include "structure/elements/ElementKind.hpp"

namespace fsi::structure {

/// A bar material (the scene's `type: bar`): E, A, ρ.
struct BarMaterial {
  std::string name;
  double young = 0;    ///< Young's modulus [Pa]
  double area = 0;     ///< cross-section [m²]
  double density = 0;  ///< mass density [kg/m³]
};

/// Contiguous run of bars with one material; the kernel hoists the constants.
struct BarBlock {
  int begin = 0, end = 0;
  int material = 0;
  double axialStiffness = 0;  ///< E*A [N]
  double area = 0, density = 0;
};

/// Two-node bars, sorted by material then by first node.
struct Bars {
  int count = 0;
  std::vector<int> conn;             ///< 2 node indices per bar
  std::vector<double> restLength;    ///< L0 [m]
  std::vector<double> invWaveSpeed;  ///< 1/c = sqrt(ρ/E) per bar (changes with mass scaling)
  std::vector<BarBlock> blocks;
  std::vector<long> tag;  ///< the line's user-facing id in its mesh
  std::vector<int> mesh;
  std::vector<BarMaterial> materials;
};

/// What a mesh entry gives the bars (MeshInput::kindInputs["bar"]): the lines it claimed from the mesh
/// (mesh-local node indices), their ids and rest lengths (0: the reference distance), and the material.
struct BarInput {
  int material = -1;  ///< index into the bar materials
  std::vector<std::array<int, 2>> lines;
  std::vector<long> tags;
  std::vector<double> restLength;
};

/// The model's bars (an empty block if it has none).
const Bars& barsOf(const Model& model);

class BarKind final : public ElementKind {
 public:
  std::string name() const override { return "bar"; }
  std::string label() const override { return "bars"; }
  int count(const Model& model) const override { return barsOf(model).count; }
  /// "bar 3 of mesh 'frame'".
  std::string describe(const Model& model, int element) const override;
  /// The bars of every mesh's BarInput; checks the bar materials (MaterialTable::other["bar"]: young, area,
  /// density, each positive) and every bar (a material, nodes in range, a positive length).
  void build(const std::vector<MeshInput>& inputs, const MaterialTable& materials,
             Model& model) const override;
  std::unique_ptr<Effect> makeForces(const Model& model, const ElementDamping& damping) const override;
  void addLumpedMass(const Model& model, std::vector<double>& mass) const override;
  double referenceStableDt(const Model& model) const override;
  std::optional<LimitingElement> limitingElementAt(const Model& model, int node) const override;
  ScaledMass scaleMass(Model& model, double need) const override;
  void addStiffnessBounds(const Model& model, const double* x, std::vector<double>& dofRow,
                          std::vector<double>& dofDiag) const override;
  /// "bars": Polyline cells in /mesh/bars, only when the model has bars.
  std::optional<CellSet> outputCells(const Model& model) const override;
  std::vector<std::string> outputFields() const override { return {"bar_force", "bar_strain"}; }
  void addFields(const Model& model, const double* x, const std::set<std::string>& wanted,
                 ElementFieldBuffers& buffers, std::vector<FieldView>& views) const override;
  /// max_force and min_force [N] (tension positive: a negative min_force is the largest compression).
  std::vector<std::pair<std::string, double>> report(const Model& model, const double* x) const override;
  /// The bar of largest |strain|.
  std::optional<StrainedElement> mostStrained(const Model& model, const double* x) const override;
};

}  // namespace fsi::structure
