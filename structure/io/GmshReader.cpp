#include "structure/io/GmshReader.hpp"

#include <fmt/format.h>
#include <gmsh.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <fstream>
#include <map>
#include <mutex>
#include <new>
#include <string>
#include <system_error>
#include <unordered_map>
#include <utility>
#include <vector>

#include "structure/model/Error.hpp"

namespace fsi::structure {
namespace {

// Gmsh element type numbers (MSH format).
constexpr int kLine2 = 1;
constexpr int kTriangle3 = 2;
constexpr int kQuad4 = 3;
constexpr int kPoint = 15;

// The Gmsh API is one global session: serialise readers so two threads never share it.
std::mutex& gmshMutex() {
  static std::mutex m;
  return m;
}

// Finalises the Gmsh session on every path, including exceptions.
class GmshSession {
 public:
  GmshSession() { gmsh::initialize(0, nullptr, /*readConfigFiles=*/false); }
  ~GmshSession() {
    try {
      gmsh::finalize();
    } catch (...) {
      // A destructor must not throw; nothing useful to do if Gmsh fails to shut down.
    }
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

std::string lastGmshError() {
  std::string error;
  try {
    gmsh::logger::getLastError(error);
  } catch (...) {
  }
  return error.empty() ? std::string("unknown Gmsh error") : error;
}

// Elements and nodes attached to one Gmsh entity, so physical groups can be resolved afterwards.
struct EntityContent {
  std::vector<int> triangles;
  std::vector<int> lines;
  std::vector<std::size_t> nodeTags;
};

using DimTag = std::pair<int, int>;

struct Triangle {
  std::array<std::size_t, 3> nodes;
  long tag;
};
struct Line {
  std::array<std::size_t, 2> nodes;
  long tag;
};

double squaredDistance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return dx * dx + dy * dy + dz * dz;
}

void sortUnique(std::vector<int>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

MeshData extractMesh(const std::string& where, const std::string& meshName) {
  std::vector<std::size_t> allNodeTags;
  std::vector<double> allCoords, parametric;
  gmsh::model::mesh::getNodes(allNodeTags, allCoords, parametric, -1, -1, false, false);
  std::unordered_map<std::size_t, std::array<double, 3>> coords;
  coords.reserve(allNodeTags.size());
  for (std::size_t i = 0; i < allNodeTags.size(); ++i) {
    coords[allNodeTags[i]] = {allCoords[3 * i], allCoords[3 * i + 1], allCoords[3 * i + 2]};
  }
  const auto coordOf = [&](std::size_t nodeTag, long elementTag) -> const std::array<double, 3>& {
    const auto it = coords.find(nodeTag);
    if (it == coords.end()) {
      throw InputError(fmt::format("Gmsh mesh '{}': element {} refers to node {}, which does not exist",
                                   where, elementTag, nodeTag));
    }
    return it->second;
  };

  std::vector<Triangle> triangles;
  std::vector<Line> lines;
  std::map<DimTag, EntityContent> entities;

  // MSH 2.2 stores an element once per physical group of its entity, under different tags: without this
  // check a surface in two groups would get every membrane twice. Copies with the same node sequence are
  // merged into the first one read (whose tag is kept).
  std::map<std::array<std::size_t, 3>, int> triangleIndex;
  std::map<std::array<std::size_t, 2>, int> lineIndex;
  const auto addTriangle = [&](const std::array<std::size_t, 3>& nodes, long tag, EntityContent& content) {
    const auto [it, isNew] = triangleIndex.emplace(nodes, static_cast<int>(triangles.size()));
    if (isNew) triangles.push_back({nodes, tag});
    content.triangles.push_back(it->second);
  };
  const auto addLine = [&](const std::array<std::size_t, 2>& nodes, long tag, EntityContent& content) {
    const auto [it, isNew] = lineIndex.emplace(nodes, static_cast<int>(lines.size()));
    if (isNew) lines.push_back({nodes, tag});
    content.lines.push_back(it->second);
  };

  gmsh::vectorpair dimTags;
  gmsh::model::getEntities(dimTags, -1);
  for (const auto& [dim, tag] : dimTags) {
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> elementTags, nodeTags;
    gmsh::model::mesh::getElements(types, elementTags, nodeTags, dim, tag);
    EntityContent& content = entities[{dim, tag}];
    for (std::size_t t = 0; t < types.size(); ++t) {
      const auto& tags = elementTags[t];
      const auto& nodes = nodeTags[t];
      switch (types[t]) {
        case kPoint:
          content.nodeTags.insert(content.nodeTags.end(), nodes.begin(), nodes.end());
          break;
        case kLine2:
          for (std::size_t e = 0; e < tags.size(); ++e) {
            addLine({nodes[2 * e], nodes[2 * e + 1]}, static_cast<long>(tags[e]), content);
          }
          break;
        case kTriangle3:
          for (std::size_t e = 0; e < tags.size(); ++e) {
            addTriangle({nodes[3 * e], nodes[3 * e + 1], nodes[3 * e + 2]}, static_cast<long>(tags[e]),
                        content);
          }
          break;
        case kQuad4:
          for (std::size_t e = 0; e < tags.size(); ++e) {
            const long elementTag = static_cast<long>(tags[e]);
            const std::size_t a = nodes[4 * e], b = nodes[4 * e + 1], c = nodes[4 * e + 2],
                              d = nodes[4 * e + 3];
            // The shorter diagonal gives the better-shaped pair; both halves keep the quad's node order.
            const bool splitAC = squaredDistance(coordOf(a, elementTag), coordOf(c, elementTag)) <=
                                 squaredDistance(coordOf(b, elementTag), coordOf(d, elementTag));
            if (splitAC) {
              addTriangle({a, b, c}, elementTag, content);
              addTriangle({a, c, d}, elementTag, content);
            } else {
              addTriangle({a, b, d}, elementTag, content);
              addTriangle({b, c, d}, elementTag, content);
            }
          }
          break;
        default: {
          std::string typeName;
          int typeDim = 0, order = 0, numNodes = 0, numPrimary = 0;
          std::vector<double> localCoords;
          gmsh::model::mesh::getElementProperties(types[t], typeName, typeDim, order, numNodes, localCoords,
                                                  numPrimary);
          throw InputError(fmt::format(
              "Gmsh mesh '{}': element {} has unsupported Gmsh element type {} ('{}'); supported types are "
              "2-node lines (1), 3-node triangles (2) and 4-node quadrangles (3), points (15) are ignored",
              where, tags.empty() ? 0 : tags.front(), types[t], typeName));
        }
      }
    }
  }
  if (triangles.empty() && lines.empty()) {
    throw InputError(
        fmt::format("Gmsh mesh '{}': the file contains no line, triangle or quadrangle elements", where));
  }

  // Points: only the nodes used by kept elements, in ascending tag order.
  std::vector<std::size_t> used;
  for (const auto& tri : triangles) used.insert(used.end(), tri.nodes.begin(), tri.nodes.end());
  for (const auto& line : lines) used.insert(used.end(), line.nodes.begin(), line.nodes.end());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());

  MeshData mesh;
  mesh.name = meshName;
  std::unordered_map<std::size_t, int> indexOf;
  indexOf.reserve(used.size());
  mesh.points.reserve(used.size());
  mesh.pointTags.reserve(used.size());
  for (const std::size_t nodeTag : used) {
    const auto it = coords.find(nodeTag);
    if (it == coords.end()) {
      throw InputError(
          fmt::format("Gmsh mesh '{}': an element refers to node {}, which does not exist", where, nodeTag));
    }
    indexOf[nodeTag] = static_cast<int>(mesh.points.size());
    mesh.points.push_back(it->second);
    mesh.pointTags.push_back(static_cast<long>(nodeTag));
  }
  for (const auto& tri : triangles) {
    mesh.triangles.push_back({indexOf[tri.nodes[0]], indexOf[tri.nodes[1]], indexOf[tri.nodes[2]]});
    mesh.triangleTags.push_back(tri.tag);
  }
  for (const auto& line : lines) {
    mesh.lines.push_back({indexOf[line.nodes[0]], indexOf[line.nodes[1]]});
    mesh.lineTags.push_back(line.tag);
  }

  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, -1);
  for (const auto& [dim, groupTag] : groups) {
    if (dim > 2) continue;  // volume groups have no membrane or cable meaning
    std::string name;
    gmsh::model::getPhysicalName(dim, groupTag, name);
    if (name.empty()) name = fmt::format("physical_{}_{}", dim, groupTag);

    std::vector<int> groupTriangles, groupLines, groupNodes;
    std::vector<int> entityTags;
    gmsh::model::getEntitiesForPhysicalGroup(dim, groupTag, entityTags);
    for (const int entityTag : entityTags) {
      const auto found = entities.find({dim, entityTag});
      if (found == entities.end()) continue;
      const EntityContent& content = found->second;
      for (const int t : content.triangles) {
        groupTriangles.push_back(t);
        groupNodes.insert(groupNodes.end(), mesh.triangles[t].begin(), mesh.triangles[t].end());
      }
      for (const int l : content.lines) {
        groupLines.push_back(l);
        groupNodes.insert(groupNodes.end(), mesh.lines[l].begin(), mesh.lines[l].end());
      }
      std::vector<std::size_t> pointNodes = content.nodeTags;
      if (dim == 0) {
        // Point entities may carry their node without a point element.
        std::vector<std::size_t> classified;
        std::vector<double> unusedCoords, unusedParametric;
        gmsh::model::mesh::getNodes(classified, unusedCoords, unusedParametric, 0, entityTag, false, false);
        pointNodes.insert(pointNodes.end(), classified.begin(), classified.end());
      }
      for (const std::size_t nodeTag : pointNodes) {
        const auto it = indexOf.find(nodeTag);
        if (it == indexOf.end()) {
          throw InputError(fmt::format(
              "Gmsh mesh '{}': physical group '{}' contains node {}, which belongs to no line or triangle",
              where, name, nodeTag));
        }
        groupNodes.push_back(it->second);
      }
    }
    sortUnique(groupNodes);
    if (dim == 2) {
      auto& target = mesh.triangleGroups[name];
      target.insert(target.end(), groupTriangles.begin(), groupTriangles.end());
      sortUnique(target);
    } else if (dim == 1) {
      auto& target = mesh.lineGroups[name];
      target.insert(target.end(), groupLines.begin(), groupLines.end());
      sortUnique(target);
    }
    // Groups of different dimensions may share a name: their nodes are merged.
    auto& nodes = mesh.nodeGroups[name];
    nodes.insert(nodes.end(), groupNodes.begin(), groupNodes.end());
    sortUnique(nodes);
  }
  return mesh;
}

}  // namespace

MeshData readGmsh(const std::filesystem::path& file, const std::string& meshName) {
  const std::string where = file.string();
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) {
    throw InputError(fmt::format("Gmsh mesh '{}': file not found", where));
  }
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw InputError(fmt::format("Gmsh mesh '{}': not a regular file", where));
  }
  // Gmsh reports an unreadable file only through its log, so check readability here.
  if (!std::ifstream(file, std::ios::binary)) {
    throw InputError(fmt::format("Gmsh mesh '{}': file cannot be opened for reading", where));
  }

  const std::lock_guard<std::mutex> lock(gmshMutex());
  const GmshSession session;
  try {
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 1);
    gmsh::open(where);
    return extractMesh(where, meshName);
  } catch (const InputError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::string& message) {  // Gmsh 4.8 throws its error message as a std::string
    throw InputError(fmt::format("Gmsh mesh '{}': Gmsh cannot read it: {}", where, message));
  } catch (const std::exception& e) {
    throw InputError(fmt::format("Gmsh mesh '{}': Gmsh cannot read it: {}", where, e.what()));
  } catch (...) {
    throw InputError(fmt::format("Gmsh mesh '{}': Gmsh cannot read it: {}", where, lastGmshError()));
  }
}

}  // namespace fsi::structure
