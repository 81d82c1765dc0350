// MSH 2.0-2.2 $Nodes and $Elements. In this version an element carries its own physical and elementary
// (entity) tags; an element in several physical groups is written once per group, under different tags.

#include <fmt/format.h>

#include <algorithm>
#include <climits>
#include <cstdint>
#include <set>
#include <utility>

#include "structure/io/MshSections.hpp"

namespace fsi::structure::msh {

namespace {

constexpr long long kMaxTag = LLONG_MAX;

// Smallest possible size of one item, for checkCount: text needs a digit and a separator per number.
std::size_t minBytes(const MshInput& in, std::size_t numbers, std::size_t binaryBytes) {
  return in.binary() ? binaryBytes : 2 * numbers;
}

// Adds the element's entity (created even without physical groups) and its physical group. `seen` makes
// this O(log n) when elements of one entity name many different groups.
void addEntity(MshContent& mesh, const MshContent::DimTag& entity, long long physical,
               std::set<std::pair<MshContent::DimTag, int>>& seen) {
  std::vector<int>& groups = mesh.entities[entity];
  if (physical <= 0 || (!groups.empty() && groups.back() == int(physical))) return;
  if (seen.insert({entity, int(physical)}).second) groups.push_back(int(physical));
}

void addElementNodes(MshInput& in, MshContent& mesh, const NodeIndex& index, long long tag, int count,
                     bool binary32) {
  for (int k = 0; k < count; ++k) {
    const long long node =
        binary32 ? in.int32("a node tag", 1, INT32_MAX) : in.size("a node tag", 1, kMaxTag);
    const int i = index.find(node);
    if (i < 0) in.fail(fmt::format("element {} refers to node {}, which is not in $Nodes", tag, node));
    mesh.elementNodes.push_back(i);
  }
}

}  // namespace

void readNodes2(MshInput& in, MshContent& mesh, NodeIndex& index, bool parametric) {
  const long long count = in.textInteger("the number of nodes", 0, INT_MAX);
  in.checkCount(count, minBytes(in, parametric ? 6 : 4, parametric ? 4 + 3 * 8 + 8 : 4 + 3 * 8), "nodes");
  if (in.binary()) in.endLine();
  index.reserve(count, kMaxTag);
  mesh.nodeTags.reserve(std::size_t(count));
  mesh.nodeCoords.reserve(std::size_t(count));
  for (long long n = 0; n < count; ++n) {
    const long long tag = in.int32("a node tag", 1, in.binary() ? INT32_MAX : kMaxTag);
    if (!index.add(tag, int(mesh.nodeTags.size()))) in.fail(fmt::format("node {} is defined twice", tag));
    std::array<double, 3> x;
    for (double& c : x) c = in.real("a node coordinate");
    if (parametric) {
      // $ParametricNodes: the entity the node is classified on, then u (curves) or u v (surfaces).
      const int dim = int(in.int32("an entity dimension", 0, 3));
      const int entity = int(in.int32("an entity tag", 0, INT_MAX));
      if (dim == 1 || dim == 2) in.skipReals(std::size_t(dim), "a parametric coordinate");
      mesh.entities.try_emplace({dim, entity});
      if (dim == 0) mesh.pointEntityNodes.emplace_back(entity, int(mesh.nodeTags.size()));
    }
    mesh.nodeTags.push_back(long(tag));
    mesh.nodeCoords.push_back(x);
  }
  in.expect(parametric ? "$EndParametricNodes" : "$EndNodes");
}

void readElements2(MshInput& in, MshContent& mesh, const NodeIndex& index) {
  const long long count = in.textInteger("the number of elements", 0, INT_MAX);
  in.checkCount(count, minBytes(in, 4, 4 * 2), "elements");
  mesh.elements.reserve(std::size_t(count));
  std::set<std::pair<MshContent::DimTag, int>> seen;
  const auto add = [&](long long tag, int type, long long physical, long long elementary, std::size_t where) {
    MshContent::Element e;
    e.tag = long(tag);
    e.type = type;
    e.entity = {elementDimension(type), int(elementary)};
    e.first = mesh.elementNodes.size();
    e.where = where;
    addEntity(mesh, e.entity, physical, seen);
    mesh.elements.push_back(e);
  };

  if (!in.binary()) {
    // elm-number elm-type number-of-tags <tags> node-number-list; tags: physical, elementary, partitions.
    for (long long n = 0; n < count; ++n) {
      const long long tag = in.textInteger("an element tag", 1, kMaxTag);
      const std::size_t where = in.mark();
      const long long type = in.textInteger("an element type", INT_MIN, INT_MAX);
      if (elementDimension(int(type)) < 0) failUnsupportedType(in, tag, type);
      const long long numTags = in.textInteger("the number of element tags", 0, INT_MAX);
      in.checkCount(numTags, 2, "element tags");
      long long physical = 0, elementary = 0;
      for (long long t = 0; t < numTags; ++t) {
        if (t == 0)
          physical = in.textInteger("a physical tag", 0, INT_MAX);
        else if (t == 1)
          elementary = in.textInteger("an elementary tag", 0, INT_MAX);
        else
          in.textInteger("a partition tag", INT_MIN, INT_MAX);
      }
      add(tag, int(type), physical, elementary, where);
      addElementNodes(in, mesh, index, tag, mshNodesPerElement(int(type)), false);
    }
  } else {
    // Blocks: a header (elm-type, number of elements that follow, number of tags), then per element
    // elm-number, the tags and the nodes, all 4-byte ints.
    in.endLine();
    long long done = 0;
    while (done < count) {
      const long long type = in.int32("an element type", INT_MIN, INT_MAX);
      const long long follow = in.int32("the number of elements in a block", 1, count - done);
      const long long numTags = in.int32("the number of element tags", 0, INT_MAX);
      if (elementDimension(int(type)) < 0)
        failUnsupportedType(in, in.int32("an element tag", 1, INT32_MAX), type);
      const int numNodes = mshNodesPerElement(int(type));
      in.checkCount(follow, 4 * std::size_t(1 + numTags + numNodes), "elements");
      for (long long n = 0; n < follow; ++n) {
        const long long tag = in.int32("an element tag", 1, INT32_MAX);
        const std::size_t where = in.mark();
        long long physical = 0, elementary = 0;
        for (long long t = 0; t < numTags; ++t) {
          if (t == 0)
            physical = in.int32("a physical tag", 0, INT32_MAX);
          else if (t == 1)
            elementary = in.int32("an elementary tag", 0, INT32_MAX);
          else
            in.int32("a partition tag", INT32_MIN, INT32_MAX);
        }
        add(tag, int(type), physical, elementary, where);
        addElementNodes(in, mesh, index, tag, numNodes, true);
      }
      done += follow;
    }
  }
  in.expect("$EndElements");
}

}  // namespace fsi::structure::msh
