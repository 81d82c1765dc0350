#include <fmt/format.h>

#include "structure/model/Error.hpp"
#include "structure/scene/JoinNames.hpp"
#include "structure/scene/MeshSources.hpp"
#include "structure/scene/NearestName.hpp"
#include "structure/scene/SceneSpec.hpp"

namespace fsi::structure {

namespace {

// `point_masses: {NODE_GROUP: MATERIAL, ...}`: every node of the mesh's node group carries one point mass of
// the point_mass material (a payload on the parafoil's `payload` node).
std::vector<std::array<int, 2>> readPointMasses(const YamlMap& pm, const MeshData& mesh,
                                                const std::map<std::string, int>& idx) {
  std::vector<std::array<int, 2>> out;
  if (pm.keys().empty()) pm.fail("give at least one 'NODE_GROUP: MATERIAL' pair, or leave point_masses out");
  std::vector<std::string> groups;
  for (const auto& kv : mesh.nodeGroups) groups.push_back(kv.first);
  for (const auto& group : pm.keys()) {
    const int material = materialRef(pm, group, idx, "point_mass");
    const auto it = mesh.nodeGroups.find(group);
    if (it == mesh.nodeGroups.end()) {
      const std::string near = closestMatch(group, groups);
      pm.failAt(group, fmt::format("the mesh has no node group '{}'{}; its node groups: {}", group,
                                   near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near),
                                   groups.empty() ? "(none)" : joinNames(groups)));
    }
    if (it->second.empty()) pm.failAt(group, fmt::format("node group '{}' is empty", group));
    for (int node : it->second) out.push_back({node, material});
  }
  return out;
}

}  // namespace

std::vector<MeshSpec> readMeshes(const YamlMap& top, const MaterialTable& materials,
                                 const std::filesystem::path& dir) {
  const auto& membraneIdx = materialsOfKind(materials, "membrane");
  const auto& cableIdx = materialsOfKind(materials, "cable");
  const auto& pointMassIdx = materialsOfKind(materials, "point_mass");
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
    if (m.has("point_masses")) in.pointMasses = readPointMasses(m.map("point_masses"), in.mesh, pointMassIdx);
    m.finish({"file", "generator", "material", "cable_material", "point_masses"});
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
    return buildModel(std::move(inputs), materials.membrane, materials.cable, materials.pointMass);
  } catch (const InputError& e) {
    const std::string what = e.what();
    std::string where = file;
    for (const auto& [name, origin] : meshOrigins)
      if (what.find("mesh '" + name + "'") != std::string::npos) where = origin;
    throw InputError(where + ": " + what);
  }
}

}  // namespace fsi::structure
