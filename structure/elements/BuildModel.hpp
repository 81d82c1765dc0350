#pragma once
// buildModel: the Model from its meshes and materials. Above model/ (docs/ARCHITECTURE.md "Layers") because
// every registered element kind builds its own block and adds its lumped masses (elementKinds()).

#include <vector>

#include "structure/model/Materials.hpp"
#include "structure/model/Model.hpp"

namespace fsi::structure {

/// Builds a Model: merges the meshes' nodes and renumbers them, lets every registered element kind build its
/// own block from its cells (ElementKind::build, in registry order: reference geometry, constants, and the
/// rejection of degenerate input — zero-area triangles, zero-length lines, repeated nodes in an element —
/// with an InputError naming the element), sums the lumped masses and rejects a massless node.
Model buildModel(std::vector<MeshInput> meshes, const MaterialTable& materials);
/// The same for membranes and cables only.
Model buildModel(std::vector<MeshInput> meshes, std::vector<MembraneMaterial> membraneMaterials,
                 std::vector<CableMaterial> cableMaterials);

}  // namespace fsi::structure
