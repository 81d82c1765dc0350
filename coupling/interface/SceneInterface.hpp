#pragma once
// SceneInterface: the fluid–structure interface a structure scene declares with
// `coupling: {interface: <triangles>}`, as an InterfaceMesh in the reference configuration. One code path for
// the coupled run (StructureParticipant) and the pre-flight check (`fsi map-check SCENE.yaml CASE:patch`), so
// the check sees exactly the mesh the coupling will use.

#include <filesystem>
#include <string>
#include <vector>

#include "coupling/interface/InterfaceMesh.hpp"
#include "structure/scene/Scene.hpp"

namespace fsi::coupling {

/// The scene's interface triangles: point i is the i-th node of the scene's coupling interface (the
/// order of every per-node array of a coupled run), at its reference position; faces are the interface
/// triangles. Throws fsi::InputError naming the scene file when it declares no `coupling` interface.
InterfaceMesh sceneInterface(const structure::Scene& scene);

/// True for a structure scene file name (`.yaml` or `.yml`).
bool isSceneFile(const std::string& spec);

/// Loads the scene (with `--set`-style overrides) and returns its interface, named `sceneFile`.
InterfaceMesh readSceneInterface(const std::filesystem::path& sceneFile,
                                 const std::vector<std::string>& overrides = {});

/// What `fsi map-check` accepts on either side: a scene file (`SCENE.yaml`, its coupling interface; the
/// overrides apply to it) or any form of readInterface (FILE.msh, FILE.msh:GROUP, CASE_DIR:PATCH).
InterfaceMesh readInterfaceOrScene(const std::string& spec,
                                   const std::vector<std::string>& sceneOverrides = {});

}  // namespace fsi::coupling
