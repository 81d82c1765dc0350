#include "structure/elements/PointMassElement.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "structure/model/Error.hpp"
#include "structure/model/MaterialKeys.hpp"

namespace fsi::structure {

const PointMasses& pointMassesOf(const Model& model) {
  static const PointMasses none;
  const PointMasses* P = model.block<PointMasses>("point_mass");
  return P ? *P : none;
}

std::string PointMassKind::describe(const Model& model, int element) const {
  const PointMasses& P = pointMassesOf(model);
  return fmt::format("point mass {} of mesh '{}'", P.tag[element], model.meshes[P.mesh[element]].name);
}

void PointMassKind::build(const std::vector<MeshInput>& inputs, const MaterialTable& materials,
                          Model& model) const {
  PointMasses P;
  P.materials = materials.pointMass;
  for (const auto& m : P.materials) checkMaterial(m);  // the key's range and message (model/MaterialKeys)
  for (std::size_t m = 0; m < inputs.size(); ++m) {
    const auto it = inputs[m].kindInputs.find(name());
    if (it == inputs[m].kindInputs.end()) continue;
    const MeshData& md = inputs[m].mesh;
    long number = 0;
    for (const auto& [local, material] : std::any_cast<const PointMassInput&>(it->second)) {
      ++number;
      if (local < 0 || local >= int(md.points.size()))
        throw MeshInputError(
            int(m), fmt::format("mesh '{}': point mass {} refers to node index {} out of range", md.name,
                                number, local));
      if (material < 0 || material >= int(P.materials.size()))
        throw MeshInputError(
            int(m), fmt::format("mesh '{}': point mass {} has no point_mass material", md.name, number));
      P.node.push_back(model.meshes[m].node[local]);
      P.mass.push_back(P.materials[material].mass);
      P.tag.push_back(number);
      P.mesh.push_back(int(m));
    }
  }
  P.count = int(P.node.size());
  model.kindBlocks[name()] = std::move(P);
}

std::unique_ptr<Effect> PointMassKind::makeForces(const Model& /*model*/,
                                                  const ElementDamping& /*damping*/) const {
  return nullptr;
}

void PointMassKind::addLumpedMass(const Model& model, std::vector<double>& mass) const {
  const PointMasses& P = pointMassesOf(model);
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

std::vector<std::pair<std::string, double>> PointMassKind::report(const Model& model,
                                                                  const double* /*x*/) const {
  const PointMasses& P = pointMassesOf(model);
  if (P.count == 0) return {};
  double total = 0;
  for (const double m : P.mass) total += m;
  return {{"total_mass", total}};
}

// No stiffness: nothing to add to the Gerschgorin bounds.
void PointMassKind::addStiffnessBounds(const Model& /*model*/, const double* /*x*/,
                                       std::vector<double>& /*dofRow*/,
                                       std::vector<double>& /*dofDiag*/) const {}

}  // namespace fsi::structure
