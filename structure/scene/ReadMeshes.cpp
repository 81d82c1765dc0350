#include <fmt/format.h>

#include "structure/model/Error.hpp"
#include "structure/scene/MeshSources.hpp"
#include "structure/scene/SceneSpec.hpp"

namespace fsi::structure {

std::vector<MeshSpec> readMeshes(const YamlMap& top, const MaterialTable& materials,
                                 const std::filesystem::path& dir) {
  const auto& membraneIdx = materialsOfKind(materials, "membrane");
  const auto& cableIdx = materialsOfKind(materials, "cable");
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
    if (m.has("material")) in.membraneMaterial = materialRef(m, "material", membraneIdx, "membrane");
    if (m.has("cable_material")) in.cableMaterial = materialRef(m, "cable_material", cableIdx, "cable");
    m.finish({"file", "generator", "material", "cable_material"});
    if (!in.mesh.triangles.empty() && in.membraneMaterial < 0)
      m.fail("this mesh has triangles: give it a membrane 'material'");
    if (!in.mesh.lines.empty() && in.cableMaterial < 0)
      m.fail("this mesh has lines: give it a 'cable_material'");
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
    return buildModel(std::move(inputs), materials.membrane, materials.cable);
  } catch (const InputError& e) {
    const std::string what = e.what();
    std::string where = file;
    for (const auto& [name, origin] : meshOrigins)
      if (what.find("mesh '" + name + "'") != std::string::npos) where = origin;
    throw InputError(where + ": " + what);
  }
}

}  // namespace fsi::structure
