#pragma once
// A scene file as read and validated, before anything is built from it: plain data (title, materials,
// meshes with their origin, solver, time, output). The sections that select parts of the model (sets,
// constraints, effects, coupling, probes) are not in it: a selector can only be checked against the built
// model, so their builders read them from the document (SetResolver, BuildConstraints, effects/,
// ReadCoupling, probes/), through YamlMap, with located errors.
//
// Data flow (docs/ARCHITECTURE.md, "From scene file to run state"):
//   YAML text --readSceneSpec--> SceneSpec --buildScene--> Scene (model, constraints, effects, probes,
//   controls)

#include <filesystem>
#include <string>
#include <vector>

#include "structure/model/Model.hpp"
#include "structure/scene/ReadMaterials.hpp"
#include "structure/scene/RunControls.hpp"

namespace fsi::structure {

/// One entry of `meshes:`: the mesh (read or generated) with its material indices, and where it came from
/// (the .msh file and the scene entry) for the model builder's messages.
struct MeshSpec {
  MeshInput input;
  std::string name;
  std::string origin;
};

struct SceneSpec {
  std::string file;           ///< the scene file name, as used in messages
  std::filesystem::path dir;  ///< relative mesh paths are resolved here
  std::string title;
  MaterialTable materials;
  std::vector<MeshSpec> meshes;
  SolverControl solver;
  TimeControl time;
  OutputControl output;
  bool relaxation() const { return solver.type == SolverControl::Type::DynamicRelaxation; }
};

/// Reads `meshes:` (each one read from its file or generated) of the top-level map `top`.
std::vector<MeshSpec> readMeshes(const YamlMap& top, const MaterialTable& materials,
                                 const std::filesystem::path& dir);

/// Builds the Model from the meshes and materials; a model error is located at the mesh it names.
Model buildSceneModel(std::vector<MeshSpec> meshes, const MaterialTable& materials, const std::string& file);

}  // namespace fsi::structure
