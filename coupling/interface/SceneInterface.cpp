#include "coupling/interface/SceneInterface.hpp"

#include <unordered_map>

#include "coupling/interface/InterfaceIO.hpp"
#include "structure/effects/InterfacePressure.hpp"
#include "structure/model/Error.hpp"
#include "structure/model/Model.hpp"

namespace fsi::coupling {

namespace {

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

}  // namespace

InterfaceMesh sceneInterface(const structure::Scene& scene) {
  if (!scene.couplingInterface)
    throw InputError(scene.file.string() +
                     ": the scene declares no coupling interface; add `coupling: {interface: <triangles>}`");
  const structure::Nodes& N = scene.model->nodes;
  const std::vector<int>& nodes = scene.couplingInterface->nodes;
  InterfaceMesh mesh;
  mesh.name = "structure";
  std::unordered_map<int, int> local;  // model node -> interface point
  mesh.points.reserve(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    local[nodes[i]] = int(i);
    mesh.points.push_back({N.X[3 * nodes[i]], N.X[3 * nodes[i] + 1], N.X[3 * nodes[i] + 2]});
  }
  const std::vector<int>& tris = scene.couplingInterface->triangles;
  for (std::size_t e = 0; e + 2 < tris.size(); e += 3)
    mesh.addFace({local.at(tris[e]), local.at(tris[e + 1]), local.at(tris[e + 2])});
  return mesh;
}

bool isSceneFile(const std::string& spec) {
  return endsWith(spec, ".yaml") || endsWith(spec, ".yml");
}

InterfaceMesh readSceneInterface(const std::filesystem::path& sceneFile,
                                 const std::vector<std::string>& overrides) {
  InterfaceMesh m = sceneInterface(structure::loadScene(sceneFile, overrides));
  m.name = sceneFile.string();
  return m;
}

InterfaceMesh readInterfaceOrScene(const std::string& spec, const std::vector<std::string>& sceneOverrides) {
  if (isSceneFile(spec)) return readSceneInterface(spec, sceneOverrides);
  // Neither form readInterface knows (no ':', no .msh, not a folder): name all forms, the scene included.
  if (!spec.empty() && spec.find(':') == std::string::npos && !endsWith(spec, ".msh") &&
      !std::filesystem::is_directory(spec))
    throw InputError("'" + spec + "': expected FILE.msh, FILE.msh:GROUP, CASE_DIR:PATCH or SCENE.yaml");
  return readInterface(spec);
}

}  // namespace fsi::coupling
