#pragma once
// `fsi generate`: the meshes a scene builds, as designed or as a run left them.

#include <filesystem>
#include <string>
#include <vector>

namespace fsi::app {

/// Every mesh of the scene as built (generators run, files read), before the model renumbers it: MESH.msh
/// with its groups as physical groups, and for meshes with triangles MESH.stl of the outer surface (the
/// `skin` set when the mesh has one, e.g. a parafoil; otherwise every triangle), ready for snappyHexMesh.
/// With `deformed` (a run folder, its results.h5, or a state file of a run of this scene) the points are
/// moved to that run's last frame: node for node from a state file; from a results file the displacement is
/// interpolated onto this scene's mesh (so the scene may sample the same geometry finer, e.g. a fluid's
/// skin). Throws fsi::InputError naming the file for a source that is not a run of this geometry.
int generateCommand(const std::filesystem::path& scenePath, const std::filesystem::path& outDir,
                    const std::vector<std::string>& sets, const std::filesystem::path& deformed);

}  // namespace fsi::app
