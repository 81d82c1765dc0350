#include "structure/io/MeshFileWriters.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>

#include "structure/io/AtomicFile.hpp"

namespace fsi::structure {

namespace {

// Writes `body(out)` through io/AtomicFile: a temporary file, synced and renamed into place.
template <class Fn>
void writeAtomically(const std::filesystem::path& file, const char* who, Fn body) {
  replaceFileAtomically(file, who, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(fmt::format("{}: cannot create the file", tmp.string()));
    body(out);
    out.flush();
    if (!out) throw std::runtime_error(fmt::format("{}: writing failed (disk full?)", tmp.string()));
  });
}

// For every entity of one kind (count n, groups by name): the sorted list of groups of each entity.
std::vector<std::vector<std::string>> membership(std::size_t n,
                                                 const std::map<std::string, std::vector<int>>& g) {
  std::vector<std::vector<std::string>> m(n);
  for (const auto& [name, members] : g)
    for (int i : members)
      if (i >= 0 && std::size_t(i) < n) m[std::size_t(i)].push_back(name);
  return m;
}

std::string quoted(const std::string& name) {
  std::string q;
  for (char c : name) q += (c == '"' || c == '\n' || c == '\r') ? '_' : c;
  return "\"" + q + "\"";
}

}  // namespace

void writeMsh(const MeshData& mesh, const std::filesystem::path& file) {
  // Physical tags: one per (dimension, name), numbered from 1 in each dimension.
  std::map<std::pair<int, std::string>, int> physical;
  auto tagsOf = [&](int dim, const std::map<std::string, std::vector<int>>& groups) {
    int next = 1;
    for (const auto& kv : groups) physical[{dim, kv.first}] = next++;
  };
  tagsOf(2, mesh.triangleGroups);
  tagsOf(1, mesh.lineGroups);
  tagsOf(0, mesh.nodeGroups);
  const auto triGroups = membership(mesh.triangles.size(), mesh.triangleGroups);
  const auto lineGroups = membership(mesh.lines.size(), mesh.lineGroups);
  const auto nodeGroups = membership(mesh.points.size(), mesh.nodeGroups);

  struct Record {
    int type;
    int physicalTag;
    int entity;
    std::vector<int> nodes;
  };
  std::vector<Record> first, copies;  // every element once first (keeps its tag order), then the repeats
  auto add = [&](int dim, int type, const std::vector<std::vector<std::string>>& groups, std::size_t i,
                 const std::vector<int>& nodes, std::map<std::vector<std::string>, int>& entities) {
    const auto& gs = groups[i];
    const int entity = entities.emplace(gs, int(entities.size()) + 1).first->second;
    if (gs.empty()) {
      if (type != 15) first.push_back({type, 0, entity, nodes});
      return;
    }
    for (std::size_t k = 0; k < gs.size(); ++k)
      (k == 0 ? first : copies).push_back({type, physical.at({dim, gs[k]}), entity, nodes});
  };
  std::map<std::vector<std::string>, int> e2, e1, e0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    add(2, 2, triGroups, t, {mesh.triangles[t][0], mesh.triangles[t][1], mesh.triangles[t][2]}, e2);
  for (std::size_t l = 0; l < mesh.lines.size(); ++l)
    add(1, 1, lineGroups, l, {mesh.lines[l][0], mesh.lines[l][1]}, e1);
  for (std::size_t p = 0; p < mesh.points.size(); ++p) add(0, 15, nodeGroups, p, {int(p)}, e0);

  writeAtomically(file, "MSH writer", [&](std::ofstream& out) {
    out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
    out << "$PhysicalNames\n" << physical.size() << "\n";
    for (const auto& [key, tag] : physical)
      out << key.first << " " << tag << " " << quoted(key.second) << "\n";
    out << "$EndPhysicalNames\n$Nodes\n" << mesh.points.size() << "\n";
    for (std::size_t i = 0; i < mesh.points.size(); ++i)
      out << fmt::format("{} {:.17g} {:.17g} {:.17g}\n", i + 1, mesh.points[i][0], mesh.points[i][1],
                         mesh.points[i][2]);
    out << "$EndNodes\n$Elements\n" << first.size() + copies.size() << "\n";
    long tag = 0;
    for (const auto* list : {&first, &copies})
      for (const Record& r : *list) {
        out << ++tag << " " << r.type << " 2 " << r.physicalTag << " " << r.entity;
        for (int n : r.nodes) out << " " << n + 1;
        out << "\n";
      }
    out << "$EndElements\n";
  });
}

void writeStlFacet(std::ostream& out, const std::array<double, 3>& a, const std::array<double, 3>& b,
                   const std::array<double, 3>& c) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (double& x : n) x = len > 0 ? x / len : 0.0;
  out << fmt::format("  facet normal {:.9g} {:.9g} {:.9g}\n    outer loop\n", n[0], n[1], n[2]);
  for (const auto* p : {&a, &b, &c})
    out << fmt::format("      vertex {:.17g} {:.17g} {:.17g}\n", (*p)[0], (*p)[1], (*p)[2]);
  out << "    endloop\n  endfacet\n";
}

void writeStl(const MeshData& mesh, const std::vector<int>& triangles, const std::filesystem::path& file,
              const std::string& solid) {
  std::string name;
  for (char c : solid) name += (c == ' ' || c == '\n' || c == '\r' || c == '\t') ? '_' : c;
  writeAtomically(file, "STL writer", [&](std::ofstream& out) {
    out << "solid " << name << "\n";
    auto facet = [&](const std::array<int, 3>& t) {
      writeStlFacet(out, mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]);
    };
    if (triangles.empty()) {
      for (const auto& t : mesh.triangles) facet(t);
    } else {
      for (int t : triangles) facet(mesh.triangles.at(std::size_t(t)));
    }
    out << "endsolid " << name << "\n";
  });
}

}  // namespace fsi::structure
