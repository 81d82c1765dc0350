// MSH 4.1 $Entities, $Nodes and $Elements. Nodes and elements come in blocks, one per entity; physical
// groups are given per entity in $Entities. In binary files counts and tags are 8-byte size_t, entity
// numbers 4-byte ints, reals 8-byte doubles; in ASCII files the same fields are text.

#include <fmt/format.h>

#include <algorithm>
#include <climits>
#include <cstdlib>
#include <set>

#include "structure/io/MshSections.hpp"
#include "structure/model/Error.hpp"

namespace fsi::structure::msh {

namespace {

constexpr long long kMaxTag = LLONG_MAX;

std::size_t minBytes(const MshInput& in, std::size_t numbers, std::size_t binaryBytes) {
  return in.binary() ? binaryBytes : 2 * numbers;
}

struct BlockHeader {
  long long blocks, count, minTag, maxTag;
};

// numEntityBlocks numItems minTag maxTag, with the counts checked against the file size.
BlockHeader readHeader(MshInput& in, const char* items, std::size_t minItemBytes) {
  BlockHeader h;
  h.blocks = in.size("the number of entity blocks", 0, INT_MAX);
  in.checkCount(h.blocks, minBytes(in, 4, 3 * 4 + 8), "entity blocks");
  h.count = in.size(items, 0, INT_MAX);
  in.checkCount(h.count, minItemBytes, items);
  h.minTag = in.size("the smallest tag", 0, kMaxTag);
  h.maxTag = in.size("the largest tag", 0, kMaxTag);
  if (h.count > 0 && (h.minTag < 1 || h.minTag > h.maxTag))
    in.fail(fmt::format("the tag range [{}, {}] is not a range of positive tags", h.minTag, h.maxTag));
  return h;
}

}  // namespace

void readEntities4(MshInput& in, MshContent& mesh) {
  if (in.binary()) in.endLine();
  long long counts[4];
  const char* names[4] = {"point entities", "curve entities", "surface entities", "volume entities"};
  // A point: tag, x y z, number of physical tags; others: tag, bounding box, two counts.
  const std::size_t textNumbers[4] = {5, 9, 9, 9},
                    binaryBytes[4] = {4 + 24 + 8, 4 + 48 + 16, 4 + 48 + 16, 4 + 48 + 16};
  for (int d = 0; d < 4; ++d) {
    counts[d] = in.size(names[d], 0, INT_MAX);
    in.checkCount(counts[d], minBytes(in, textNumbers[d], binaryBytes[d]), names[d]);
  }
  std::set<MshContent::DimTag> seen;
  for (int dim = 0; dim < 4; ++dim) {
    for (long long e = 0; e < counts[dim]; ++e) {
      const long long tag = in.int32("an entity tag", 0, INT_MAX);
      const std::size_t where = in.mark();
      in.skipReals(dim == 0 ? 3 : 6, dim == 0 ? "a point's coordinates" : "an entity's bounding box");
      const long long numPhysicals = in.size("the number of physical tags", 0, INT_MAX);
      in.checkCount(numPhysicals, minBytes(in, 1, 4), "physical tags");
      std::vector<int> physicals;
      for (long long p = 0; p < numPhysicals; ++p) {
        // The sign gives an orientation; the group is the absolute value (as Gmsh reads it).
        const long long physical = in.int32("a physical tag", -INT_MAX, INT_MAX);
        if (physical == 0) in.fail("physical tag 0 (physical tags are non-zero)");
        physicals.push_back(int(std::llabs(physical)));
      }
      if (dim > 0) {
        const long long numBounding = in.size("the number of bounding entities", 0, INT_MAX);
        in.checkCount(numBounding, minBytes(in, 1, 4), "bounding entities");
        for (long long b = 0; b < numBounding; ++b) in.int32("a bounding entity tag", INT_MIN, INT_MAX);
      }
      if (!seen.insert({dim, int(tag)}).second)
        throw InputError(
            fmt::format("{}: in $Entities: entity ({}, {}) is defined twice", in.where(where), dim, tag));
      std::vector<int>& groups = mesh.entities[{dim, int(tag)}];
      groups.insert(groups.end(), physicals.begin(), physicals.end());
    }
  }
  in.expect("$EndEntities");
}

void readNodes4(MshInput& in, MshContent& mesh, NodeIndex& index) {
  if (in.binary()) in.endLine();
  const BlockHeader h = readHeader(in, "nodes", minBytes(in, 4, 8 + 3 * 8));
  index.reserve(h.count, h.maxTag);
  mesh.nodeTags.reserve(std::size_t(h.count));
  mesh.nodeCoords.reserve(std::size_t(h.count));
  long long done = 0;
  for (long long b = 0; b < h.blocks; ++b) {
    const int dim = int(in.int32("an entity dimension", 0, 3));
    const int entity = int(in.int32("an entity tag", 0, INT_MAX));
    const bool parametric = in.int32("the parametric flag", 0, 1) == 1;
    const long long n = in.size("the number of nodes in a block", 0, h.count - done);
    mesh.entities.try_emplace({dim, entity});
    for (long long k = 0; k < n; ++k) {
      const long long tag = in.size("a node tag", h.minTag, h.maxTag);
      if (!index.add(tag, int(mesh.nodeTags.size()))) in.fail(fmt::format("node {} is defined twice", tag));
      mesh.nodeTags.push_back(long(tag));
      if (dim == 0) mesh.pointEntityNodes.emplace_back(entity, int(mesh.nodeTags.size() - 1));
    }
    // Parametric coordinates follow x y z on curves (u) and surfaces (u v).
    const std::size_t extra = parametric && (dim == 1 || dim == 2) ? std::size_t(dim) : 0;
    for (long long k = 0; k < n; ++k) {
      std::array<double, 3> x;
      for (double& c : x) c = in.real("a node coordinate");
      if (extra > 0) in.skipReals(extra, "a parametric coordinate");
      mesh.nodeCoords.push_back(x);
    }
    done += n;
  }
  if (done != h.count)
    in.fail(fmt::format("the header announces {} nodes, but the blocks hold {}", h.count, done));
  in.expect("$EndNodes");
}

void readElements4(MshInput& in, MshContent& mesh, const NodeIndex& index) {
  if (in.binary()) in.endLine();
  const BlockHeader h = readHeader(in, "elements", minBytes(in, 2, 16));
  mesh.elements.reserve(std::size_t(h.count));
  long long done = 0;
  for (long long b = 0; b < h.blocks; ++b) {
    const int dim = int(in.int32("an entity dimension", 0, 3));
    const int entity = int(in.int32("an entity tag", 0, INT_MAX));
    const long long type = in.int32("an element type", INT_MIN, INT_MAX);
    const long long n = in.size("the number of elements in a block", 0, h.count - done);
    if (elementDimension(int(type)) < 0)
      failUnsupportedType(in, n > 0 ? in.size("an element tag", 0, kMaxTag) : 0, type);
    if (elementDimension(int(type)) != dim)
      in.fail(fmt::format("elements of type {} ('{}') in a block of an entity of dimension {}", type,
                          mshElementTypeName(int(type)), dim));
    const int numNodes = mshNodesPerElement(int(type));
    in.checkCount(n, minBytes(in, std::size_t(1 + numNodes), 8 * std::size_t(1 + numNodes)), "elements");
    mesh.entities.try_emplace({dim, entity});
    for (long long k = 0; k < n; ++k) {
      MshContent::Element e;
      e.tag = long(in.size("an element tag", h.minTag, h.maxTag));
      e.where = in.mark();
      e.type = int(type);
      e.entity = {dim, entity};
      e.first = mesh.elementNodes.size();
      for (int j = 0; j < numNodes; ++j) {
        const long long node = in.size("a node tag", 1, kMaxTag);
        const int i = index.find(node);
        if (i < 0) in.fail(fmt::format("element {} refers to node {}, which is not in $Nodes", e.tag, node));
        mesh.elementNodes.push_back(i);
      }
      mesh.elements.push_back(e);
    }
    done += n;
  }
  if (done != h.count)
    in.fail(fmt::format("the header announces {} elements, but the blocks hold {}", h.count, done));
  in.expect("$EndElements");
}

}  // namespace fsi::structure::msh
