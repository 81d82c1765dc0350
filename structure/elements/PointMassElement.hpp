#pragma once
// The point mass as an element kind: a lumped mass on one node (a payload). It has no internal force, no
// stiffness and no wave speed, so it adds no force effect, does not bound the stable step and is never
// mass-scaled; its only contribution is its mass, which is physical mass (gravity acts on it, body drag and
// probes see it). The kind owns its block of the model (PointMasses, in model.kindBlocks) and the building of
// that block; its scene reader (structure/scene/kinds/PointMassKeys.cpp) reads its mesh key
// (`point_masses: {NODE_GROUP: MATERIAL}`) into a PointMassInput.

#include <array>
#include <vector>

#include "structure/elements/ElementKind.hpp"

namespace fsi::structure {

/// Point masses: a lumped mass on one node each, no internal force, no stiffness.
struct PointMasses {
  int count = 0;
  std::vector<int> node;     ///< model node carrying the mass
  std::vector<double> mass;  ///< [kg]
  std::vector<long> tag;     ///< 1-based number of the point mass within its mesh
  std::vector<int> mesh;
  std::vector<PointMassMaterial> materials;
};

/// What a mesh entry's `point_masses:` says (MeshInput::kindInputs["point_mass"]): (mesh-local node index,
/// index into the point-mass materials), one per carrying node.
using PointMassInput = std::vector<std::array<int, 2>>;

/// The model's point masses (an empty block if it has none).
const PointMasses& pointMassesOf(const Model& model);

class PointMassKind final : public ElementKind {
 public:
  std::string name() const override { return "point_mass"; }
  std::string label() const override { return "point masses"; }
  int count(const Model& model) const override { return pointMassesOf(model).count; }
  /// "point mass 1 of mesh 'wing'".
  std::string describe(const Model& model, int element) const override;
  /// The point masses in mesh order, each mesh's in the order of its `point_masses:` entry.
  void build(const std::vector<MeshInput>& inputs, const MaterialTable& materials,
             Model& model) const override;
  /// None: a point mass resists nothing but acceleration.
  std::unique_ptr<Effect> makeForces(const Model& model, const ElementDamping& damping) const override;
  void addLumpedMass(const Model& model, std::vector<double>& mass) const override;
  double referenceStableDt(const Model& model) const override;
  ScaledMass scaleMass(Model& model, double need) const override;
  void addStiffnessBounds(const Model& model, const double* x, std::vector<double>& dofRow,
                          std::vector<double>& dofDiag) const override;
  /// total_mass [kg].
  std::vector<std::pair<std::string, double>> report(const Model& model, const double* x) const override;
};

}  // namespace fsi::structure
