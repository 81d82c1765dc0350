// The cable's scene keys: `cable_material: NAME` (a cable material) for the mesh's lines, `cables:` (which
// line groups of a mesh file are cables; the others stay node sets) and `edge_cables:` (a cable on every
// boundary edge of the triangles within a node group). Lines another kind claimed (bars) are no longer the
// mesh's when this reads.
#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <set>

#include "structure/scene/ReadMaterials.hpp"
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/YamlAccess.hpp"
#include "structure/scene/kinds/KindReaders.hpp"
#include "structure/scene/kinds/LineGroups.hpp"

namespace fsi::structure {

namespace {

// Keeps the lines of the named groups (all of them for "all") as the mesh's cables; every other line group
// becomes a node group of its nodes (a Physical Curve named for a constraint or a probe, not a cable).
void keepCableGroups(MeshData& mesh, const std::vector<std::string>& names, const YamlMap& entry) {
  const bool all = names.size() == 1 && names[0] == "all";
  std::vector<char> keep(mesh.lines.size(), all ? 1 : 0);
  if (!all)
    for (const std::string& n : names) {
      const auto it = mesh.lineGroups.find(n);
      if (it == mesh.lineGroups.end()) {
        entry.failAt("cables", fmt::format("the mesh has no line group (Physical Curve) '{}'; it has: {}", n,
                                           groupList(mesh.lineGroups)));
      }
      for (const int e : it->second) keep[std::size_t(e)] = 1;
    }
  std::vector<int> index(mesh.lines.size(), -1);
  std::vector<std::array<int, 2>> lines;
  std::vector<long> tags;
  std::vector<double> rest;
  for (std::size_t e = 0; e < mesh.lines.size(); ++e) {
    if (!keep[e]) continue;
    index[e] = int(lines.size());
    lines.push_back(mesh.lines[e]);
    if (e < mesh.lineTags.size()) tags.push_back(mesh.lineTags[e]);
    if (e < mesh.lineRestLength.size()) rest.push_back(mesh.lineRestLength[e]);
  }
  std::map<std::string, std::vector<int>> groups;
  for (auto& [name, members] : mesh.lineGroups) {
    std::vector<int> kept;
    std::set<int> nodes;
    for (const int e : members) {
      if (index[std::size_t(e)] >= 0) kept.push_back(index[std::size_t(e)]);
      nodes.insert(mesh.lines[std::size_t(e)][0]);
      nodes.insert(mesh.lines[std::size_t(e)][1]);
    }
    if (!kept.empty()) groups[name] = std::move(kept);
    // its nodes stay a node set under the same name (joined with a node group of that name, if any)
    std::vector<int>& ng = mesh.nodeGroups[name];
    nodes.insert(ng.begin(), ng.end());
    ng.assign(nodes.begin(), nodes.end());
  }
  mesh.lines = std::move(lines);
  mesh.lineTags = std::move(tags);
  mesh.lineRestLength = std::move(rest);
  mesh.lineGroups = std::move(groups);
}

// edge_cables: a cable on every boundary edge of the mesh's triangles (an edge of one triangle only) whose
// two nodes are in the named node group, under a line group of the same name: a tape or a rope along a
// generated membrane's edge without a mesh file.
void addEdgeCables(MeshData& mesh, const std::vector<std::string>& names, const YamlMap& entry) {
  std::map<std::pair<int, int>, int> edgeUse;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = t[std::size_t(k)], b = t[std::size_t((k + 1) % 3)];
      ++edgeUse[{std::min(a, b), std::max(a, b)}];
    }
  for (const std::string& name : names) {
    const auto it = mesh.nodeGroups.find(name);
    if (it == mesh.nodeGroups.end()) {
      entry.failAt("edge_cables", fmt::format("the mesh has no node group '{}'; it has: {}", name,
                                              groupList(mesh.nodeGroups)));
    }
    const std::set<int> nodes(it->second.begin(), it->second.end());
    std::vector<int>& group = mesh.lineGroups[name];
    const std::size_t before = group.size();
    for (const auto& [edge, uses] : edgeUse)
      if (uses == 1 && nodes.count(edge.first) && nodes.count(edge.second)) {
        group.push_back(int(mesh.lines.size()));
        mesh.lines.push_back({edge.first, edge.second});
        mesh.lineTags.push_back(long(mesh.lines.size()));
      }
    if (group.size() == before)
      entry.failAt("edge_cables", fmt::format("the node group '{}' has no edge on the boundary of the mesh's "
                                              "triangles: no cable to lay along it",
                                              name));
  }
  if (!mesh.lineRestLength.empty()) mesh.lineRestLength.resize(mesh.lines.size(), 0.0);
}

void read(const YamlMap& entry, const MaterialTable& materials, MeshInput& in) {
  if (entry.has("cable_material"))
    in.cableMaterial = materialRef(entry, "cable_material", materialsOfKind(materials, "cable"), "cable");
  // Which line elements of a mesh file are cables is said, not assumed: a Physical Curve may name nodes for a
  // constraint or a probe. A generator's lines are its cables (suspension lines, tapes).
  if (entry.has("cables")) {
    const YAML::Node n = entry.raw("cables");
    const std::vector<std::string> names =
        n.IsScalar() ? std::vector<std::string>{entry.choice("cables", {"all"})} : entry.strings("cables");
    keepCableGroups(in.mesh, names, entry);
  } else if (entry.has("file") && !in.mesh.lines.empty()) {
    if (in.cableMaterial >= 0) {
      entry.fail(fmt::format(
          "this mesh file has line elements (Physical Curves: {}) and a cable_material: say which are cables "
          "with 'cables: [NAMES]' or 'cables: all' (the others stay node sets for constraints and probes)",
          groupList(in.mesh.lineGroups)));
    }
    keepCableGroups(in.mesh, {}, entry);  // no cable material: every curve is a node set
  }
  if (entry.has("edge_cables")) addEdgeCables(in.mesh, entry.strings("edge_cables"), entry);
}

void check(const YamlMap& entry, const MeshInput& in) {
  if (!in.mesh.lines.empty() && in.cableMaterial < 0)
    entry.fail("this mesh has cables: give it a 'cable_material'");
}

const SchemaSection& schema() {
  static const SchemaSection s{
      "meshes.NAME (cable)",
      "the cable's keys of a mesh entry",
      {{"cable_material",
        KeyType::String,
        "",
        "",
        "required with lines",
        {},
        {},
        {},
        "a `type: cable` material for the mesh's lines"},
       {"cables",
        KeyType::Strings,
        "",
        "",
        "a generator's lines; none of a file's",
        {},
        {},
        {},
        "the line groups (Physical Curves) of a mesh file that are cables, or `all`; the others stay node "
        "sets"},
       {"edge_cables",
        KeyType::Strings,
        "",
        "",
        "none",
        {},
        {},
        {},
        "node groups: a cable on every boundary edge of the triangles with both nodes in the group"}}};
  return s;
}

}  // namespace

KindReader cableReader() {
  return {"cable", &schema(), nullptr, read, check};
}

}  // namespace fsi::structure
