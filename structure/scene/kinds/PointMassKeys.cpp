// The point mass's scene key: `point_masses: {NODE_GROUP: MATERIAL, ...}` (point_mass materials).
#include <fmt/format.h>

#include "structure/elements/PointMassElement.hpp"
#include "structure/scene/JoinNames.hpp"
#include "structure/scene/NearestName.hpp"
#include "structure/scene/ReadMaterials.hpp"
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/YamlAccess.hpp"
#include "structure/scene/kinds/KindReaders.hpp"

namespace fsi::structure {

namespace {

// `point_masses: {NODE_GROUP: MATERIAL, ...}`: every node of the mesh's node group carries one point mass of
// the point_mass material (a payload on the parafoil's `payload` node).
void read(const YamlMap& entry, const MaterialTable& materials, MeshInput& in) {
  if (!entry.has("point_masses")) return;
  const YamlMap pm = entry.map("point_masses");
  const auto& idx = materialsOfKind(materials, "point_mass");
  const MeshData& mesh = in.mesh;
  PointMassInput out;
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
  in.kindInputs["point_mass"] = std::move(out);
}

const SchemaSection& schema() {
  static const SchemaSection s{
      "meshes.NAME (point_mass)",
      "the point mass's keys of a mesh entry",
      {{"point_masses",
        KeyType::Map,
        "",
        "",
        "none",
        {},
        {},
        {},
        "`{NODE_GROUP: MATERIAL, ...}`: a `type: point_mass` material on every node of "
        "the group"}}};
  return s;
}

}  // namespace

KindReader pointMassReader() {
  return {"point_mass", &schema(), nullptr, read, nullptr};
}

}  // namespace fsi::structure
