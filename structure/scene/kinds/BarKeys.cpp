// The bar's scene keys: `bars: [LINE_GROUPS]` or `bars: all` (which lines of the mesh are bars: the kind
// claims them, the other lines stay the cables' or node sets) and `bar_material: NAME` (a `type: bar`
// material). A claimed group's nodes stay a node set under its name (for constraints and probes).
#include <fmt/format.h>

#include <set>

#include "structure/elements/BarElement.hpp"
#include "structure/scene/ReadMaterials.hpp"
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/YamlAccess.hpp"
#include "structure/scene/kinds/KindReaders.hpp"
#include "structure/scene/kinds/LineGroups.hpp"

namespace fsi::structure {

namespace {

// Moves the lines of the named groups (every line for "all") from the mesh into `out`.
void takeLines(MeshData& mesh, const std::vector<std::string>& names, const YamlMap& entry, BarInput& out) {
  const bool all = names.size() == 1 && names[0] == "all";
  std::vector<char> take(mesh.lines.size(), all ? 1 : 0);
  if (!all)
    for (const std::string& n : names) {
      const auto it = mesh.lineGroups.find(n);
      if (it == mesh.lineGroups.end())
        entry.failAt("bars", fmt::format("the mesh has no line group (Physical Curve) '{}'; it has: {}", n,
                                         groupList(mesh.lineGroups)));
      for (const int e : it->second) take[std::size_t(e)] = 1;
    }
  if (mesh.lines.empty() || std::find(take.begin(), take.end(), 1) == take.end())
    entry.failAt("bars", "these line groups have no line: no bar to make");
  std::vector<int> index(mesh.lines.size(), -1);
  MeshData rest;
  for (std::size_t e = 0; e < mesh.lines.size(); ++e) {
    const long tag = e < mesh.lineTags.size() ? mesh.lineTags[e] : long(e + 1);
    const double L0 = e < mesh.lineRestLength.size() ? mesh.lineRestLength[e] : 0.0;
    if (take[e]) {
      out.lines.push_back(mesh.lines[e]);
      out.tags.push_back(tag);
      out.restLength.push_back(L0);
      continue;
    }
    index[e] = int(rest.lines.size());
    rest.lines.push_back(mesh.lines[e]);
    if (e < mesh.lineTags.size()) rest.lineTags.push_back(tag);
    if (e < mesh.lineRestLength.size()) rest.lineRestLength.push_back(L0);
  }
  for (auto& [name, members] : mesh.lineGroups) {
    std::vector<int> kept;
    std::set<int> nodes;
    for (const int e : members) {
      if (index[std::size_t(e)] >= 0) {
        kept.push_back(index[std::size_t(e)]);
        continue;
      }
      nodes.insert(mesh.lines[std::size_t(e)][0]);
      nodes.insert(mesh.lines[std::size_t(e)][1]);
    }
    if (!kept.empty()) rest.lineGroups[name] = std::move(kept);
    if (nodes.empty()) continue;
    std::vector<int>& ng = mesh.nodeGroups[name];  // the bars' nodes stay a node set under the group's name
    nodes.insert(ng.begin(), ng.end());
    ng.assign(nodes.begin(), nodes.end());
  }
  mesh.lines = std::move(rest.lines);
  mesh.lineTags = std::move(rest.lineTags);
  mesh.lineRestLength = std::move(rest.lineRestLength);
  mesh.lineGroups = std::move(rest.lineGroups);
}

void claim(const YamlMap& entry, const MaterialTable& materials, MeshInput& in) {
  if (!entry.has("bars")) {
    if (entry.has("bar_material"))
      entry.failAt("bar_material", "say which lines are bars: 'bars: [LINE_GROUPS]' or 'bars: all'");
    return;
  }
  if (!entry.has("bar_material"))
    entry.failAt("bars", "these lines are bars: give the mesh a 'bar_material'");
  BarInput bars;
  bars.material = materialRef(entry, "bar_material", materialsOfKind(materials, "bar"), "bar");
  const YAML::Node n = entry.raw("bars");
  const std::vector<std::string> names =
      n.IsScalar() ? std::vector<std::string>{entry.choice("bars", {"all"})} : entry.strings("bars");
  takeLines(in.mesh, names, entry, bars);
  in.kindInputs["bar"] = std::move(bars);
}

const SchemaSection& schema() {
  static const SchemaSection s{
      "meshes.NAME (bar)",
      "the bar's keys of a mesh entry",
      {{"bar_material",
        KeyType::String,
        "",
        "",
        "required with bars",
        {},
        {},
        {},
        "a `type: bar` material for the lines that are bars"},
       {"bars",
        KeyType::Strings,
        "",
        "",
        "none",
        {},
        {},
        {},
        "the line groups that are bars, or `all`; their nodes stay a node set under the group's name"}}};
  return s;
}

}  // namespace

KindReader barReader() {
  return {"bar", &schema(), claim, nullptr, nullptr};
}

}  // namespace fsi::structure
