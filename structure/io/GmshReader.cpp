#include "structure/io/GmshReader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <new>
#include <numeric>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "structure/io/MshReader.hpp"
#include "structure/model/Error.hpp"

namespace fsi::structure {
namespace {

using DimTag = MshContent::DimTag;

// What one entity holds once duplicates are merged: indices into the kept triangles and lines, and the
// nodes of its point elements or classified on it (indices into MshContent::nodeTags).
struct EntityContent {
  std::vector<int> triangles;
  std::vector<int> lines;
  std::vector<int> pointNodes;
};

struct Triangle {
  std::array<int, 3> nodes;  // indices into MshContent::nodeTags
  long tag;
};
struct Line {
  std::array<int, 2> nodes;
  long tag;
};

// Finds the first copy of an element (same node sequence) among those kept so far: open addressing over
// indices into the kept elements, sized once for all of them (a node-based hash map was a third of the
// read time of a million triangles).
template <class Element>
class FirstCopies {
 public:
  explicit FirstCopies(std::size_t capacity) {
    std::size_t size = 16;
    while (size < 2 * capacity) size *= 2;
    slots_.assign(size, -1);
  }
  /// Index into `kept` of the element with these nodes; appends one with `tag` if there is none yet.
  int findOrAdd(const decltype(Element::nodes)& nodes, long tag, std::vector<Element>& kept) {
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (const int v : nodes) h = (h ^ std::uint64_t(std::uint32_t(v))) * 0xff51afd7ed558ccdull;
    for (std::size_t i = std::size_t(h ^ (h >> 29)) & (slots_.size() - 1);;
         i = (i + 1) & (slots_.size() - 1)) {
      if (slots_[i] < 0) {
        slots_[i] = int(kept.size());
        kept.push_back({nodes, tag});
        return slots_[i];
      }
      const auto& other = kept[std::size_t(slots_[i])].nodes;
      if (std::equal(nodes.begin(), nodes.end(), other.begin())) return slots_[i];
    }
  }

 private:
  std::vector<int> slots_;
};

// Sorts `v` and removes repeats; `universe` bounds the values (a bitmap beats sorting for long lists).
void sortUnique(std::vector<int>& v, std::size_t universe) {
  if (v.size() > universe / 8) {
    std::vector<char> present(universe, 0);
    for (const int x : v) present[std::size_t(x)] = 1;
    v.clear();
    for (std::size_t x = 0; x < universe; ++x)
      if (present[x]) v.push_back(int(x));
    return;
  }
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

double squaredDistance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return dx * dx + dy * dy + dz * dz;
}

MeshData buildMesh(const MshContent& msh, const std::string& meshName) {
  const std::string& where = msh.file;
  // Elements in the order the Gmsh library gave them to the earlier reader (results must not depend on
  // the reader): by entity (dimension, then tag), triangles before quadrangles, file order otherwise.
  std::vector<std::size_t> order(msh.elements.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  const auto key = [&](std::size_t i) {
    const MshContent::Element& e = msh.elements[i];
    return std::tie(e.entity, e.type);
  };
  const auto before = [&](std::size_t a, std::size_t b) { return key(a) < key(b); };
  if (!std::is_sorted(order.begin(), order.end(), before))
    std::stable_sort(order.begin(), order.end(), before);

  std::vector<Triangle> triangles;
  std::vector<Line> lines;
  std::map<DimTag, EntityContent> entities;
  for (const auto& [entity, physicals] : msh.entities) entities[entity];

  // MSH 2 stores an element once per physical group of its entity, under different tags: without this
  // check a surface in two groups would get every membrane twice. Copies with the same node sequence are
  // merged into the first one read (whose tag is kept).
  std::size_t maxTriangles = 0, maxLines = 0;
  for (const MshContent::Element& e : msh.elements) {
    maxTriangles += e.type == kMshTriangle3 ? 1 : (e.type == kMshQuad4 ? 2 : 0);
    maxLines += e.type == kMshLine2 ? 1 : 0;
  }
  FirstCopies<Triangle> triangleCopies(maxTriangles);
  FirstCopies<Line> lineCopies(maxLines);
  triangles.reserve(maxTriangles);
  lines.reserve(maxLines);
  const auto addTriangle = [&](const std::array<int, 3>& nodes, long tag, EntityContent& content) {
    content.triangles.push_back(triangleCopies.findOrAdd(nodes, tag, triangles));
  };
  const auto addLine = [&](const std::array<int, 2>& nodes, long tag, EntityContent& content) {
    content.lines.push_back(lineCopies.findOrAdd(nodes, tag, lines));
  };

  for (const std::size_t i : order) {
    const MshContent::Element& e = msh.elements[i];
    const int* n = msh.elementNodes.data() + e.first;
    EntityContent& content = entities[e.entity];
    switch (e.type) {
      case kMshPoint:
        content.pointNodes.push_back(n[0]);
        break;
      case kMshLine2:
        addLine({n[0], n[1]}, e.tag, content);
        break;
      case kMshTriangle3:
        addTriangle({n[0], n[1], n[2]}, e.tag, content);
        break;
      case kMshQuad4: {
        const auto& x = msh.nodeCoords;
        // The shorter diagonal gives the better-shaped pair; both halves keep the quad's node order.
        if (squaredDistance(x[std::size_t(n[0])], x[std::size_t(n[2])]) <=
            squaredDistance(x[std::size_t(n[1])], x[std::size_t(n[3])])) {
          addTriangle({n[0], n[1], n[2]}, e.tag, content);
          addTriangle({n[0], n[2], n[3]}, e.tag, content);
        } else {
          addTriangle({n[0], n[1], n[3]}, e.tag, content);
          addTriangle({n[1], n[2], n[3]}, e.tag, content);
        }
        break;
      }
      default:  // MshReader keeps no other type
        throw InputError(fmt::format("{}: element {} of type {}", msh.where(e.where), e.tag, e.type));
    }
  }
  for (const auto& [entityTag, node] : msh.pointEntityNodes)
    entities[{0, entityTag}].pointNodes.push_back(node);
  if (triangles.empty() && lines.empty())
    throw InputError(fmt::format("{}: the file contains no line, triangle or quadrangle elements", where));

  // Points: only the nodes used by kept elements, in ascending tag order.
  const std::size_t numNodes = msh.nodeTags.size();
  std::vector<char> isUsed(numNodes, 0);
  for (const Triangle& t : triangles)
    for (const int v : t.nodes) isUsed[std::size_t(v)] = 1;
  for (const Line& l : lines)
    for (const int v : l.nodes) isUsed[std::size_t(v)] = 1;
  std::vector<int> used;
  for (std::size_t v = 0; v < numNodes; ++v)
    if (isUsed[v]) used.push_back(int(v));
  const auto byTag = [&](int a, int b) {
    return msh.nodeTags[std::size_t(a)] < msh.nodeTags[std::size_t(b)];
  };
  if (!std::is_sorted(used.begin(), used.end(), byTag)) std::sort(used.begin(), used.end(), byTag);

  MeshData mesh;
  mesh.name = meshName;
  std::vector<int> indexOf(numNodes, -1);
  mesh.points.reserve(used.size());
  mesh.pointTags.reserve(used.size());
  for (const int v : used) {
    indexOf[std::size_t(v)] = static_cast<int>(mesh.points.size());
    mesh.points.push_back(msh.nodeCoords[std::size_t(v)]);
    mesh.pointTags.push_back(msh.nodeTags[std::size_t(v)]);
  }
  mesh.triangles.reserve(triangles.size());
  mesh.triangleTags.reserve(triangles.size());
  for (const Triangle& t : triangles) {
    mesh.triangles.push_back({indexOf[std::size_t(t.nodes[0])], indexOf[std::size_t(t.nodes[1])],
                              indexOf[std::size_t(t.nodes[2])]});
    mesh.triangleTags.push_back(t.tag);
  }
  mesh.lines.reserve(lines.size());
  mesh.lineTags.reserve(lines.size());
  for (const Line& l : lines) {
    mesh.lines.push_back({indexOf[std::size_t(l.nodes[0])], indexOf[std::size_t(l.nodes[1])]});
    mesh.lineTags.push_back(l.tag);
  }

  // Physical groups: (dimension, tag) -> its entities.
  std::map<DimTag, std::set<DimTag>> groups;
  for (const auto& [entity, physicals] : msh.entities)
    for (const int p : physicals) groups[{entity.first, p}].insert(entity);
  // Each group lists its members: a file that puts entities into very many groups would make the output
  // grow as groups x elements. Real meshes have a handful of groups per element; refuse the absurd.
  std::size_t listed = 0;
  for (const auto& [group, members] : groups)
    for (const DimTag& entity : members) {
      const EntityContent& c = entities.at(entity);
      listed += c.triangles.size() + c.lines.size() + c.pointNodes.size();
    }
  const std::size_t items = mesh.triangles.size() + mesh.lines.size() + msh.pointEntityNodes.size();
  if (listed > 100 * items + 1000000)
    throw InputError(
        fmt::format("{}: its {} physical groups would list {} elements and nodes, more than 100 "
                    "groups per element",
                    where, groups.size(), listed));
  for (const auto& [group, members] : groups) {
    const auto [dim, groupTag] = group;
    if (dim > 2) continue;  // volume groups have no membrane or cable meaning
    const auto named = msh.physicalNames.find(group);
    const std::string name = named == msh.physicalNames.end() || named->second.empty()
                                 ? fmt::format("physical_{}_{}", dim, groupTag)
                                 : named->second;
    std::vector<int> groupTriangles, groupLines, groupNodes;
    for (const DimTag& entity : members) {
      const EntityContent& content = entities.at(entity);
      for (const int t : content.triangles) {
        groupTriangles.push_back(t);
        groupNodes.insert(groupNodes.end(), mesh.triangles[std::size_t(t)].begin(),
                          mesh.triangles[std::size_t(t)].end());
      }
      for (const int l : content.lines) {
        groupLines.push_back(l);
        groupNodes.insert(groupNodes.end(), mesh.lines[std::size_t(l)].begin(),
                          mesh.lines[std::size_t(l)].end());
      }
      for (const int v : content.pointNodes) {
        if (indexOf[std::size_t(v)] < 0)
          throw InputError(
              fmt::format("{}: physical group '{}' contains node {}, which belongs to no line or "
                          "triangle",
                          where, name, msh.nodeTags[std::size_t(v)]));
        groupNodes.push_back(indexOf[std::size_t(v)]);
      }
    }
    sortUnique(groupNodes, mesh.points.size());
    if (dim == 2) {
      auto& target = mesh.triangleGroups[name];
      target.insert(target.end(), groupTriangles.begin(), groupTriangles.end());
      sortUnique(target, mesh.triangles.size());
    } else if (dim == 1) {
      auto& target = mesh.lineGroups[name];
      target.insert(target.end(), groupLines.begin(), groupLines.end());
      sortUnique(target, mesh.lines.size());
    }
    // Groups of different dimensions may share a name: their nodes are merged.
    auto& nodes = mesh.nodeGroups[name];
    nodes.insert(nodes.end(), groupNodes.begin(), groupNodes.end());
    sortUnique(nodes, mesh.points.size());
  }
  return mesh;
}

}  // namespace

MeshData readGmsh(const std::filesystem::path& file, const std::string& meshName) {
  const MshContent msh = readMshFile(file);
  try {
    return buildMesh(msh, meshName);
  } catch (const std::bad_alloc&) {
    throw InputError(fmt::format("{}: not enough memory to build this mesh", file.string()));
  }
}

}  // namespace fsi::structure
