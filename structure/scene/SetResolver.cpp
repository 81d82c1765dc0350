#include "structure/scene/SetResolver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "structure/model/Error.hpp"
#include "structure/scene/JoinNames.hpp"
#include "structure/scene/SelectorSchema.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure {

namespace {

template <class Groups>
std::vector<std::string> groupNames(const Groups& g) {
  std::vector<std::string> n;
  for (const auto& kv : g) n.push_back(kv.first);
  return n;
}

std::string join(const std::vector<std::string>& v) {
  return joinNames(v);
}

}  // namespace

void SetResolver::define(const std::string& name, YAML::Node sel, const std::string& path) {
  named_[name] = {std::move(sel), path};
}

std::vector<int> SetResolver::nodes(const YAML::Node& sel, const std::string& path) const {
  std::vector<int> out = nodesRaw(sel, path);
  sortUnique(out);
  if (out.empty()) throw InputError(locate(file_, sel, path) + ": selects no nodes");
  return out;
}

void SetResolver::resolveNamed(const std::string& name) const {
  const Named& set = named_.at(name);
  if (nodesByName(name, set.sel, set.path).empty())
    throw InputError(locate(file_, set.sel, set.path) + ": selects no nodes");
}

std::vector<int> SetResolver::triangles(const YAML::Node& sel, const std::string& path) const {
  std::vector<int> out = trianglesRaw(sel, path);
  sortUnique(out);
  if (out.empty()) throw InputError(locate(file_, sel, path) + ": selects no triangles");
  return out;
}

void SetResolver::sortUnique(std::vector<int>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

// Appends a part of a union. Long unions (a list of sets that overlap, or one set listed many times) are
// deduplicated on the way so that the list never grows much beyond the number of entities.
void SetResolver::append(std::vector<int>& out, const std::vector<int>& part, std::size_t entities) {
  out.insert(out.end(), part.begin(), part.end());
  if (out.size() > 2 * entities + 1024) sortUnique(out);
}

// A named set is resolved once per kind and remembered: sets built from one another in a chain cost one
// resolution each, however deep the chain or often a set is used. `resolving_` holds the sets whose
// resolution is under way, so a set met again there closes a cycle, which is reported with its members.
template <class Resolve>
std::vector<int> SetResolver::namedSet(const std::string& name, const Named& set, const YAML::Node& at,
                                       const std::string& path, Memo& memo, Resolve resolve) const {
  if (const auto m = memo.find(name); m != memo.end()) return m->second;
  const auto open = std::find(resolving_.begin(), resolving_.end(), name);
  if (open != resolving_.end()) {
    std::string cycle;
    for (auto it = open; it != resolving_.end(); ++it) cycle += *it + " -> ";
    throw InputError(locate(file_, at, path) +
                     fmt::format(": sets refer to each other in a cycle: {}{}", cycle, name));
  }
  resolving_.push_back(name);
  std::vector<int> out;
  try {
    out = resolve(set.sel, set.path);
  } catch (...) {
    resolving_.pop_back();
    throw;
  }
  resolving_.pop_back();
  sortUnique(out);
  return memo.emplace(name, std::move(out)).first->second;
}

int SetResolver::meshIndex(const std::string& name, const YAML::Node& at, const std::string& path) const {
  for (std::size_t m = 0; m < model_.meshes.size(); ++m)
    if (model_.meshes[m].name == name) return int(m);
  std::vector<std::string> names;
  for (const auto& m : model_.meshes) names.push_back(m.name);
  for (const auto& kv : named_) names.push_back(kv.first);
  const std::string near = closestMatch(name, names);
  throw InputError(locate(file_, at, path) +
                   fmt::format(": no set or mesh named '{}'{}; known: {}", name,
                               near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near), join(names)));
}

std::vector<int> SetResolver::nodesByName(const std::string& s, const YAML::Node& at,
                                          const std::string& path) const {
  if (auto it = named_.find(s); it != named_.end())
    return namedSet(s, it->second, at, path, nodeMemo_,
                    [this](const YAML::Node& sel, const std::string& p) { return nodesRaw(sel, p); });
  const auto slash = s.find('/');
  const int m = meshIndex(s.substr(0, slash), at, path);
  const MeshMap& mm = model_.meshes[m];
  if (slash == std::string::npos) return mm.node;
  const std::string g = s.substr(slash + 1);
  std::vector<int> out;
  if (auto it = mm.source.nodeGroups.find(g); it != mm.source.nodeGroups.end()) {
    for (int i : it->second) out.push_back(mm.node[i]);
  } else if (auto t = mm.source.triangleGroups.find(g); t != mm.source.triangleGroups.end()) {
    for (int i : t->second)
      for (int k = 0; k < 3; ++k) out.push_back(mm.node[mm.source.triangles[i][k]]);
  } else if (auto l = mm.source.lineGroups.find(g); l != mm.source.lineGroups.end()) {
    for (int i : l->second)
      for (int k = 0; k < 2; ++k) out.push_back(mm.node[mm.source.lines[i][k]]);
  } else {
    auto names = groupNames(mm.source.nodeGroups);
    for (auto& n : groupNames(mm.source.triangleGroups)) names.push_back(n);
    for (auto& n : groupNames(mm.source.lineGroups)) names.push_back(n);
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    const std::string near = closestMatch(g, names);
    throw InputError(locate(file_, at, path) +
                     fmt::format(": mesh '{}' has no group '{}'{}; its groups: {}", mm.name, g,
                                 near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near),
                                 join(names)));
  }
  return out;
}

std::vector<int> SetResolver::trianglesByName(const std::string& s, const YAML::Node& at,
                                              const std::string& path) const {
  if (auto it = named_.find(s); it != named_.end())
    return namedSet(s, it->second, at, path, triangleMemo_,
                    [this](const YAML::Node& sel, const std::string& p) { return trianglesRaw(sel, p); });
  return meshElements(s, at, path, "triangle", &MeshData::triangleGroups, &MeshMap::triangle);
}

// 'mesh' (every element of the mesh) or 'mesh/group' (one of its groups of that kind), as model elements.
std::vector<int> SetResolver::meshElements(const std::string& s, const YAML::Node& at,
                                           const std::string& path, const char* kind,
                                           Groups MeshData::*groups,
                                           std::vector<int> MeshMap::*toModel) const {
  const auto slash = s.find('/');
  const MeshMap& mm = model_.meshes[meshIndex(s.substr(0, slash), at, path)];
  const std::vector<int>& map = mm.*toModel;
  std::vector<int> out;
  if (slash == std::string::npos) {
    for (int e : map)
      if (e >= 0) out.push_back(e);
    return out;
  }
  const std::string g = s.substr(slash + 1);
  const Groups& all = mm.source.*groups;
  const auto it = all.find(g);
  if (it == all.end()) {
    const auto names = groupNames(all);
    const std::string near = closestMatch(g, names);
    throw InputError(locate(file_, at, path) +
                     fmt::format(": mesh '{}' has no {} group '{}'{}; its {} groups: {}", mm.name, kind, g,
                                 near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near), kind,
                                 names.empty() ? "(none)" : join(names)));
  }
  for (int i : it->second) out.push_back(map[i]);
  return out;
}

// The union of the selections of every item of a list selector (item paths "path[i]").
template <class Resolve>
std::vector<int> SetResolver::listUnion(const YAML::Node& list, const std::string& path, std::size_t entities,
                                        Resolve resolve) {
  std::vector<int> out;
  for (std::size_t i = 0; i < list.size(); ++i)
    append(out, resolve(list[i], fmt::format("{}[{}]", path, i)), entities);
  return out;
}

std::vector<int> SetResolver::nodesRaw(const YAML::Node& sel, const std::string& path) const {
  if (sel.IsScalar()) return nodesByName(sel.Scalar(), sel, path);
  if (sel.IsSequence())
    return listUnion(sel, path, std::size_t(model_.nodes.count),
                     [this](const YAML::Node& item, const std::string& p) { return nodesRaw(item, p); });
  YamlMap m(sel, file_, path);
  const Nodes& N = model_.nodes;
  std::vector<int> out;
  if (m.has("plane")) {
    YamlMap p = m.map("plane");
    const auto pt = p.vec3("point");
    auto n = p.vec3("normal");
    p.finish({"point", "normal"});
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0)) p.failAt("normal", "must not be zero");
    const double tol = m.number("tolerance", 1e-9);
    std::vector<int> pool =
        m.has("among") ? nodesRaw(m.raw("among"), m.childPath("among")) : std::vector<int>();
    if (!m.has("among")) {
      pool.resize(N.count);
      for (int i = 0; i < N.count; ++i) pool[i] = i;
    }
    for (int i : pool) {
      double d = 0;
      for (int k = 0; k < 3; ++k) d += (N.X[3 * i + k] - pt[k]) * n[k] / len;
      if (std::abs(d) <= tol) out.push_back(i);
    }
    m.finish(planeSelectorSchema().names());
  } else if (m.has("box")) {
    YamlMap b = m.map("box");
    const auto lo = b.vec3("min"), hi = b.vec3("max");
    b.finish({"min", "max"});
    std::vector<int> pool =
        m.has("among") ? nodesRaw(m.raw("among"), m.childPath("among")) : std::vector<int>();
    if (!m.has("among")) {
      pool.resize(N.count);
      for (int i = 0; i < N.count; ++i) pool[i] = i;
    }
    for (int i : pool) {
      bool in = true;
      for (int k = 0; k < 3; ++k) in = in && N.X[3 * i + k] >= lo[k] && N.X[3 * i + k] <= hi[k];
      if (in) out.push_back(i);
    }
    m.finish(boxSelectorSchema().names());
  } else if (m.has("nearest")) {
    const auto p = m.vec3("nearest");
    std::vector<int> pool =
        m.has("among") ? nodesRaw(m.raw("among"), m.childPath("among")) : std::vector<int>();
    if (!m.has("among")) {
      pool.resize(N.count);
      for (int i = 0; i < N.count; ++i) pool[i] = i;
    }
    int best = -1;
    double bd = std::numeric_limits<double>::infinity();
    for (int i : pool) {
      double d = 0;
      for (int k = 0; k < 3; ++k) d += (N.X[3 * i + k] - p[k]) * (N.X[3 * i + k] - p[k]);
      if (d < bd) bd = d, best = i;
    }
    if (best >= 0) out.push_back(best);
    m.finish(nearestSelectorSchema().names());
  } else if (m.has("ids")) {
    const std::string mesh = m.string("mesh");
    const int mi = meshIndex(mesh, m.node(), m.path());
    const MeshMap& mm = model_.meshes[mi];
    std::map<long, int> byTag;
    for (std::size_t i = 0; i < mm.node.size(); ++i)
      byTag[i < mm.source.pointTags.size() ? mm.source.pointTags[i] : long(i + 1)] = mm.node[i];
    for (long id : m.integers("ids", {std::numeric_limits<long>::min(), std::numeric_limits<long>::max()})) {
      auto it = byTag.find(id);
      if (it == byTag.end()) m.failAt("ids", fmt::format("mesh '{}' has no node {}", mesh, id));
      out.push_back(it->second);
    }
    m.finish(idsSelectorSchema().names());
  } else {
    m.fail(
        "a node selector is a set or mesh name ('mesh/group'), a list of them, or a mapping with one of: "
        "plane, box, nearest, ids");
  }
  return out;
}

std::vector<int> SetResolver::trianglesRaw(const YAML::Node& sel, const std::string& path) const {
  if (sel.IsScalar()) return trianglesByName(sel.Scalar(), sel, path);
  if (sel.IsSequence())
    return listUnion(sel, path, std::size_t(model_.membranes.count),
                     [this](const YAML::Node& item, const std::string& p) { return trianglesRaw(item, p); });
  throw InputError(locate(file_, sel, path) +
                   ": a triangle selector is a set or mesh name ('mesh' or 'mesh/group') or a list of them");
}

std::vector<int> SetResolver::lines(const YAML::Node& sel, const std::string& path) const {
  std::vector<int> out = linesRaw(sel, path);
  sortUnique(out);
  if (out.empty()) throw InputError(locate(file_, sel, path) + ": selects no lines");
  return out;
}

std::vector<int> SetResolver::linesRaw(const YAML::Node& sel, const std::string& path) const {
  if (sel.IsSequence())
    return listUnion(sel, path, std::size_t(model_.cables.count),
                     [this](const YAML::Node& item, const std::string& p) { return linesRaw(item, p); });
  if (!sel.IsScalar())
    throw InputError(locate(file_, sel, path) +
                     ": a line selector is a mesh name ('mesh' or 'mesh/group') or a list of them");
  return meshElements(sel.Scalar(), sel, path, "line", &MeshData::lineGroups, &MeshMap::line);
}

void defineSets(const YamlMap& top, const Model& model, SetResolver& sets) {
  if (!top.has("sets")) return;
  YamlMap s = top.map("sets");
  for (const auto& name : s.keys()) {
    for (const auto& m : model.meshes)
      if (m.name == name) s.failAt(name, "a set may not have the name of a mesh");
    sets.define(name, s.raw(name), s.childPath(name));
  }
  for (const auto& name : s.keys()) {
    const YAML::Node sel = s.node()[name];
    if (sel.IsScalar() || sel.IsSequence() || sel.IsMap()) sets.resolveNamed(name);
  }
}

}  // namespace fsi::structure
