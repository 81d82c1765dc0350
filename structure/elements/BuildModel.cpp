#include "structure/elements/BuildModel.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "structure/elements/ElementKind.hpp"
#include "structure/model/Error.hpp"

namespace fsi::structure {

namespace {

// Interleaves the bits of three 21-bit integers: the Morton (Z-order) key of a point.
std::uint64_t spreadBits(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

std::vector<int> mortonOrder(const std::vector<std::array<double, 3>>& pts) {
  std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const auto& p : pts)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  double span = 0;
  for (int k = 0; k < 3; ++k) span = std::max(span, hi[k] - lo[k]);
  const double scale = span > 0 ? double((1 << 21) - 1) / span : 0.0;
  std::vector<std::uint64_t> key(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    std::uint64_t k = 0;
    for (int d = 0; d < 3; ++d) k |= spreadBits(std::uint64_t((pts[i][d] - lo[d]) * scale)) << d;
    key[i] = k;
  }
  std::vector<int> order(pts.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });
  return order;
}

}  // namespace

Model buildModel(std::vector<MeshInput> inputs, std::vector<MembraneMaterial> membraneMaterials,
                 std::vector<CableMaterial> cableMaterials) {
  MaterialTable table;
  table.membrane = std::move(membraneMaterials);
  table.cable = std::move(cableMaterials);
  return buildModel(std::move(inputs), table);
}

Model buildModel(std::vector<MeshInput> inputs, const MaterialTable& materials) {
  Model model;

  // 1. Concatenate the points of all meshes and renumber along a Morton curve.
  std::vector<std::array<double, 3>> pts, start;
  std::vector<long> tags;
  std::vector<int> meshOf;
  std::vector<int> offset;
  for (std::size_t m = 0; m < inputs.size(); ++m) {
    const MeshData& md = inputs[m].mesh;
    offset.push_back(int(pts.size()));
    for (std::size_t i = 0; i < md.points.size(); ++i) {
      pts.push_back(md.points[i]);
      start.push_back(i < md.startPoints.size() ? md.startPoints[i] : md.points[i]);
      tags.push_back(i < md.pointTags.size() ? md.pointTags[i] : long(i + 1));
      meshOf.push_back(int(m));
    }
  }
  const std::vector<int> order = mortonOrder(pts);
  std::vector<int> newIndex(pts.size());
  for (std::size_t i = 0; i < order.size(); ++i) newIndex[order[i]] = int(i);

  Nodes& N = model.nodes;
  N.count = int(pts.size());
  N.X.resize(3 * N.count);
  N.tag.resize(N.count);
  N.mesh.resize(N.count);
  for (int i = 0; i < N.count; ++i) {
    const int o = order[i];
    for (int k = 0; k < 3; ++k) N.X[3 * i + k] = pts[o][k];
    N.tag[i] = tags[o];
    N.mesh[i] = meshOf[o];
  }
  N.x.resize(3 * N.count);
  for (int i = 0; i < N.count; ++i)
    for (int k = 0; k < 3; ++k) N.x[3 * i + k] = start[order[i]][k];
  N.v.assign(3 * N.count, 0.0);
  N.fint.assign(3 * N.count, 0.0);
  N.fext.assign(3 * N.count, 0.0);
  N.mass.assign(N.count, 0.0);

  model.meshes.resize(inputs.size());
  for (std::size_t m = 0; m < inputs.size(); ++m) {
    MeshMap& mm = model.meshes[m];
    mm.name = inputs[m].mesh.name;
    mm.node.resize(inputs[m].mesh.points.size());
    for (std::size_t i = 0; i < mm.node.size(); ++i) mm.node[i] = newIndex[offset[m] + i];
  }

  // 2. Every element kind builds its own block from its cells, in registry order.
  for (const ElementKind* kind : elementKinds()) kind->build(inputs, materials, model);

  // 3. Lumped masses, each element kind adding its own.
  for (const ElementKind* kind : elementKinds()) kind->addLumpedMass(model, N.mass);
  for (int i = 0; i < N.count; ++i)
    if (!(N.mass[i] > 0))
      throw MeshInputError(N.mesh[i],
                           fmt::format("{} belongs to no element and has no mass", model.describeNode(i)));
  N.physicalMass = N.mass;
  N.invMassDof.resize(3 * N.count);
  for (int i = 0; i < N.count; ++i)
    for (int k = 0; k < 3; ++k) N.invMassDof[3 * i + k] = 1.0 / N.mass[i];
  for (std::size_t m = 0; m < inputs.size(); ++m) model.meshes[m].source = std::move(inputs[m].mesh);
  return model;
}

}  // namespace fsi::structure
