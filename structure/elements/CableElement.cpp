#include "structure/elements/CableElement.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "structure/elements/CableForces.hpp"
#include "structure/scene/ReadMaterials.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure {

std::unique_ptr<Effect> CableKind::makeForces(const Model& model, const ElementDamping& damping) const {
  return std::make_unique<CableForces>(model.cables, damping);
}

void CableKind::addLumpedMass(const Model& model, std::vector<double>& mass) const {
  const Cables& C = model.cables;
  for (const CableBlock& b : C.blocks)
    for (int e = b.begin; e < b.end; ++e) {
      const double m = 0.5 * b.density * b.area * C.restLength[e];
      mass[C.conn[2 * e]] += m;
      mass[C.conn[2 * e + 1]] += m;
    }
}

double CableKind::referenceStableDt(const Model& model) const {
  double dt = std::numeric_limits<double>::infinity();
  const Cables& C = model.cables;
  for (int e = 0; e < C.count; ++e) dt = std::min(dt, C.restLength[e] * C.invWaveSpeed[e]);
  return dt;
}

std::optional<LimitingElement> CableKind::limitingElementAt(const Model& model, int node) const {
  const Cables& C = model.cables;
  std::optional<LimitingElement> best;
  for (int e = 0; e < C.count; ++e) {
    if (C.conn[2 * e] != node && C.conn[2 * e + 1] != node) continue;
    const double dt = C.restLength[e] * C.invWaveSpeed[e];
    if (!best || dt < best->stableDt) best = LimitingElement{e, dt, C.restLength[e]};
  }
  return best;
}

ScaledMass CableKind::scaleMass(Model& model, double need) const {
  ScaledMass r;
  Cables& C = model.cables;
  std::vector<double>& mass = model.nodes.mass;
  for (const CableBlock& b : C.blocks)
    for (int e = b.begin; e < b.end; ++e) {
      const double dt = C.restLength[e] * C.invWaveSpeed[e];
      if (dt >= need) continue;
      const double s = (need / dt) * (need / dt);  // c ∝ ρ^-1/2
      const double extra = 0.5 * (s - 1.0) * b.density * b.area * C.restLength[e];
      mass[C.conn[2 * e]] += extra;
      mass[C.conn[2 * e + 1]] += extra;
      r.added += 2.0 * extra;
      C.invWaveSpeed[e] *= std::sqrt(s);
      ++r.elements;
    }
  return r;
}

void CableKind::addStiffnessBounds(const Model& model, const double* x, std::vector<double>& dofRow,
                                   std::vector<double>& dofDiag) const {
  const Cables& C = model.cables;
  for (const CableBlock& b : C.blocks)
    for (int e = b.begin; e < b.end; ++e) {
      const int i = C.conn[2 * e], j = C.conn[2 * e + 1];
      double d[3], L = 0;
      for (int k = 0; k < 3; ++k) d[k] = x[3 * j + k] - x[3 * i + k], L += d[k] * d[k];
      L = std::sqrt(L);
      const double L0 = C.restLength[e];
      const double T0 = b.axialStiffness * std::max(0.0, (L - L0) / L0);
      const double ka = b.axialStiffness / L0, kg = T0 / L;
      for (int k = 0; k < 3; ++k) {
        // K = ka e⊗e + kg (I − e⊗e) on the 2x2 node blocks [K −K; −K K]
        double row = 0;
        for (int l = 0; l < 3; ++l) {
          const double el = d[k] * d[l] / (L * L);
          row += 2.0 * std::abs(ka * el + kg * ((k == l ? 1.0 : 0.0) - el));
        }
        const double diag = ka * d[k] * d[k] / (L * L) + kg * (1.0 - d[k] * d[k] / (L * L));
        dofRow[3 * i + k] += row, dofRow[3 * j + k] += row;
        dofDiag[3 * i + k] += diag, dofDiag[3 * j + k] += diag;
      }
    }
}

void CableKind::addFields(const Model& model, const double* x, const std::set<std::string>& wanted,
                          ElementFieldBuffers& buffers, std::vector<FieldView>& views) const {
  if (model.cables.count == 0 || !wanted.count("cable_force")) return;
  buffers.arrays.resize(1);
  cableTensions(model.cables, x, buffers.arrays[0]);
  views.push_back({"cable_force", FieldView::Center::Line, 1, buffers.arrays[0].data()});
}

namespace {

// "a, b, c" of a group map's names, or "none"
std::string groupList(const std::map<std::string, std::vector<int>>& groups) {
  std::string names;
  for (const auto& [name, members] : groups) names += (names.empty() ? "" : ", ") + name;
  return names.empty() ? "none" : names;
}

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

}  // namespace

void CableKind::readMeshKeys(const YamlMap& entry, const MaterialTable& materials, MeshInput& in) const {
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

void CableKind::checkMeshInput(const YamlMap& entry, const MeshInput& in) const {
  if (!in.mesh.lines.empty() && in.cableMaterial < 0)
    entry.fail("this mesh has cables: give it a 'cable_material'");
}

}  // namespace fsi::structure
