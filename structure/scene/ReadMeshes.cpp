#include <fmt/format.h>

#include "structure/elements/BuildModel.hpp"
#include "structure/elements/ElementKind.hpp"
#include "structure/model/Error.hpp"
#include "structure/scene/MeshSources.hpp"
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/SceneSpec.hpp"
#include "structure/scene/kinds/KindReaders.hpp"

namespace fsi::structure {

std::vector<MeshSpec> readMeshes(const YamlMap& top, const MaterialTable& materials,
                                 const std::filesystem::path& dir) {
  // The valid keys of a mesh entry: where the mesh comes from, then every element kind's own (its material
  // references), in the order of the kinds' scene readers (scene/kinds, SceneSections.cpp).
  const std::vector<std::string> validKeys = meshEntrySchema().names();
  std::vector<MeshSpec> out;
  YamlMap meshes = top.map("meshes");
  if (meshes.keys().empty()) meshes.fail("at least one mesh is needed");
  for (const auto& name : meshes.keys()) {
    YamlMap m = meshes.map(name);
    MeshInput in;
    in.mesh = meshFromScene(m, name, dir);
    in.mesh.name = name;
    // Where the mesh came from, for the model builder's messages (a degenerate triangle of mesh 'canopy' is
    // in canopy.msh, or in the scene's generator entry).
    std::string origin = m.has("file") ? (dir / m.string("file")).string() + " (" +
                                             locate(m.file(), m.node(), "meshes." + name) + ")"
                                       : locate(m.file(), m.node(), "meshes." + name);
    // The kinds claim their cells first; what no kind claimed stays the defaults' (triangles: membranes,
    // lines: cables).
    for (const KindReader& r : kindReaders())
      if (r.claim) r.claim(m, materials, in);
    for (const KindReader& r : kindReaders())
      if (r.read) r.read(m, materials, in);
    m.finish(validKeys);
    for (const KindReader& r : kindReaders())
      if (r.check) r.check(m, in);
    out.push_back({std::move(in), name, std::move(origin)});
  }
  return out;
}

Model buildSceneModel(std::vector<MeshSpec> meshes, const MaterialTable& materials, const std::string& file) {
  std::vector<MeshInput> inputs;
  std::vector<std::pair<std::string, std::string>> meshOrigins;
  for (auto& m : meshes) {
    meshOrigins.emplace_back(m.name, m.origin);
    inputs.push_back(std::move(m.input));
  }
  try {
    return buildModel(std::move(inputs), materials);
  } catch (const MeshInputError& e) {
    // About one mesh: at its entry (its file, or the scene's generator entry).
    throw InputError(meshOrigins.at(std::size_t(e.mesh())).second + ": " + e.what());
  } catch (const InputError& e) {
    throw InputError(file + ": " + e.what());  // about the model as a whole (a material)
  }
}

}  // namespace fsi::structure
