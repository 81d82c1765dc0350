#include "structure/elements/BuildModel.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "structure/elements/ElementKind.hpp"
#include "structure/model/Error.hpp"
#include "structure/model/MaterialKeys.hpp"
#include "structure/model/PositiveValue.hpp"

namespace fsi::structure {

namespace {

// The materials' ranges and messages are their keys' (model/MaterialKeys): the scene reader checks the same
// entries, located at the key; this guards a Model built from materials made in code.
void checkMaterials(const std::vector<MembraneMaterial>& mm, const std::vector<CableMaterial>& cm) {
  for (const auto& m : mm) checkMaterial(m);
  for (const auto& m : cm) checkMaterial(m);
}

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
  checkMaterials(materials.membrane, materials.cable);
  Model model;
  model.membraneMaterials = materials.membrane;
  model.cableMaterials = materials.cable;

  // 1. Concatenate the points of all meshes and renumber along a Morton curve.
  std::vector<std::array<double, 3>> pts;
  std::vector<long> tags;
  std::vector<int> meshOf;
  std::vector<int> offset;
  for (std::size_t m = 0; m < inputs.size(); ++m) {
    const MeshData& md = inputs[m].mesh;
    if (!md.triangles.empty() && inputs[m].membraneMaterial < 0)
      throw MeshInputError(int(m), fmt::format("mesh '{}' has triangles but no membrane material", md.name));
    if (!md.lines.empty() && inputs[m].cableMaterial < 0)
      throw MeshInputError(int(m), fmt::format("mesh '{}' has lines but no cable material", md.name));
    offset.push_back(int(pts.size()));
    for (std::size_t i = 0; i < md.points.size(); ++i) {
      pts.push_back(md.points[i]);
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
  N.x = N.X;
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

  // 2. Membrane triangles, sorted by material then by first node.
  struct TriRef {
    int mesh, local, material, minNode;
  };
  std::vector<TriRef> tris;
  struct LineRef {
    int mesh, local, material, minNode;
  };
  std::vector<LineRef> lines;
  for (std::size_t m = 0; m < inputs.size(); ++m) {
    const MeshData& md = inputs[m].mesh;
    const auto& nm = model.meshes[m].node;
    for (std::size_t e = 0; e < md.triangles.size(); ++e) {
      const auto& t = md.triangles[e];
      for (int k = 0; k < 3; ++k)
        if (t[k] < 0 || t[k] >= int(md.points.size()))
          throw MeshInputError(
              int(m), fmt::format("mesh '{}': triangle {} refers to node index {} out of range", md.name,
                                  e < md.triangleTags.size() ? md.triangleTags[e] : long(e + 1), t[k]));
      tris.push_back({int(m), int(e), inputs[m].membraneMaterial, std::min({nm[t[0]], nm[t[1]], nm[t[2]]})});
    }
    for (std::size_t e = 0; e < md.lines.size(); ++e) {
      const auto& l = md.lines[e];
      for (int k = 0; k < 2; ++k)
        if (l[k] < 0 || l[k] >= int(md.points.size()))
          throw MeshInputError(int(m),
                               fmt::format("mesh '{}': line {} refers to node index {} out of range", md.name,
                                           e < md.lineTags.size() ? md.lineTags[e] : long(e + 1), l[k]));
      lines.push_back({int(m), int(e), inputs[m].cableMaterial, std::min(nm[l[0]], nm[l[1]])});
    }
  }
  std::stable_sort(tris.begin(), tris.end(), [](const TriRef& a, const TriRef& b) {
    return a.material != b.material ? a.material < b.material : a.minNode < b.minNode;
  });
  std::stable_sort(lines.begin(), lines.end(), [](const LineRef& a, const LineRef& b) {
    return a.material != b.material ? a.material < b.material : a.minNode < b.minNode;
  });

  MembraneTriangles& T = model.membranes;
  T.count = int(tris.size());
  T.conn.resize(3 * T.count);
  T.geo.resize(MembraneTriangles::kGeo * T.count);
  T.invWaveSpeed.resize(T.count);
  T.refStep2.resize(T.count);
  T.tag.resize(T.count);
  T.mesh.resize(T.count);
  for (auto& mm : model.meshes)
    mm.triangle.assign(inputs[&mm - model.meshes.data()].mesh.triangles.size(), -1);
  for (int e = 0; e < T.count; ++e) {
    const TriRef& r = tris[e];
    const MeshData& md = inputs[r.mesh].mesh;
    const auto& t = md.triangles[r.local];
    model.meshes[r.mesh].triangle[r.local] = e;
    T.tag[e] = r.local < int(md.triangleTags.size()) ? md.triangleTags[r.local] : long(r.local + 1);
    T.mesh[e] = r.mesh;
    int n[3];
    for (int k = 0; k < 3; ++k) n[k] = T.conn[3 * e + k] = model.meshes[r.mesh].node[t[k]];
    if (n[0] == n[1] || n[1] == n[2] || n[0] == n[2])
      throw MeshInputError(
          r.mesh, fmt::format("{} repeats a node (nodes {}, {}, {})", model.describeTriangle(e), N.tag[n[0]],
                              N.tag[n[1]], N.tag[n[2]]));
    double d21[3], d31[3];
    for (int k = 0; k < 3; ++k) {
      d21[k] = N.X[3 * n[1] + k] - N.X[3 * n[0] + k];
      d31[k] = N.X[3 * n[2] + k] - N.X[3 * n[0] + k];
    }
    const double a0 = std::sqrt(d21[0] * d21[0] + d21[1] * d21[1] + d21[2] * d21[2]);
    const double l31 = std::sqrt(d31[0] * d31[0] + d31[1] * d31[1] + d31[2] * d31[2]);
    const double b0 = a0 > 0 ? (d21[0] * d31[0] + d21[1] * d31[1] + d21[2] * d31[2]) / a0 : 0.0;
    const double c0 = std::sqrt(std::max(0.0, l31 * l31 - b0 * b0));
    const double lmax = std::max(a0, l31);
    if (!(a0 > 0) || !(c0 > 1e-9 * lmax))
      throw MeshInputError(
          r.mesh, fmt::format("{} is degenerate (zero area; nodes {}, {}, {}): check for duplicate or "
                              "collinear nodes",
                              model.describeTriangle(e), N.tag[n[0]], N.tag[n[1]], N.tag[n[2]]));
    const MembraneMaterial& mat = model.membraneMaterials[r.material];
    const double area = 0.5 * a0 * c0;
    double* g = &T.geo[MembraneTriangles::kGeo * e];
    g[0] = 1.0 / a0;
    g[1] = b0;
    g[2] = 1.0 / c0;
    g[3] = mat.thickness * area;
    T.invWaveSpeed[e] = 1.0 / membraneWaveSpeed(mat);
    const double l32 = std::sqrt((a0 - b0) * (a0 - b0) + c0 * c0);
    const double h0 = a0 * c0 / std::max({a0, l31, l32});
    T.refStep2[e] = h0 * T.invWaveSpeed[e] * h0 * T.invWaveSpeed[e];
    if (T.blocks.empty() || T.blocks.back().material != r.material) {
      MembraneBlock b;
      b.begin = e;
      b.material = r.material;
      b.young = mat.young;
      b.poisson = mat.poisson;
      b.c11 = mat.young / (1.0 - mat.poisson * mat.poisson);
      b.density = mat.density;
      b.wrinkling = mat.wrinkling;
      T.blocks.push_back(b);
    }
    T.blocks.back().end = e + 1;
  }

  // 3. Cables.
  Cables& C = model.cables;
  C.count = int(lines.size());
  C.conn.resize(2 * C.count);
  C.restLength.resize(C.count);
  C.invWaveSpeed.resize(C.count);
  C.tag.resize(C.count);
  C.mesh.resize(C.count);
  for (auto& mm : model.meshes) mm.line.assign(inputs[&mm - model.meshes.data()].mesh.lines.size(), -1);
  for (int e = 0; e < C.count; ++e) {
    const LineRef& r = lines[e];
    const MeshData& md = inputs[r.mesh].mesh;
    model.meshes[r.mesh].line[r.local] = e;
    C.tag[e] = r.local < int(md.lineTags.size()) ? md.lineTags[r.local] : long(r.local + 1);
    C.mesh[e] = r.mesh;
    const int a = C.conn[2 * e] = model.meshes[r.mesh].node[md.lines[r.local][0]];
    const int b = C.conn[2 * e + 1] = model.meshes[r.mesh].node[md.lines[r.local][1]];
    double L = 0;
    for (int k = 0; k < 3; ++k) L += std::pow(N.X[3 * b + k] - N.X[3 * a + k], 2);
    L = std::sqrt(L);
    if (a == b || !(L > 0))
      throw MeshInputError(r.mesh, fmt::format("{} has zero length (nodes {} and {})", model.describeCable(e),
                                               N.tag[a], N.tag[b]));
    const CableMaterial& mat = model.cableMaterials[r.material];
    if (std::size_t(r.local) < md.lineRestLength.size() && md.lineRestLength[std::size_t(r.local)] != 0.0) {
      // A line rigged longer than the distance of its ends: slack (no tension) until stretched to it.
      const double L0 = md.lineRestLength[std::size_t(r.local)];
      if (!(std::isfinite(L0) && L0 > 0))
        throw MeshInputError(r.mesh, fmt::format("{} has rest length {} (must be positive and finite)",
                                                 model.describeCable(e), L0));
      L = L0;
    }
    C.restLength[e] = L;
    C.invWaveSpeed[e] = std::sqrt(mat.density / mat.young);
    if (C.blocks.empty() || C.blocks.back().material != r.material) {
      CableBlock blk;
      blk.begin = e;
      blk.material = r.material;
      blk.young = mat.young;
      blk.area = mat.area;
      blk.density = mat.density;
      blk.axialStiffness = mat.young * mat.area;
      C.blocks.push_back(blk);
    }
    C.blocks.back().end = e + 1;
  }

  // 4. Every other element kind builds its own block, in registry order.
  for (const ElementKind* kind : elementKinds()) kind->build(inputs, materials, model);

  // 5. Lumped masses, each element kind adding its own.
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
