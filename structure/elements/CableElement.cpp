#include "structure/elements/CableElement.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "structure/elements/CableForces.hpp"
#include "structure/elements/TwoNodeElements.hpp"
#include "structure/model/Error.hpp"
#include "structure/model/MaterialKeys.hpp"
#include "structure/model/PositiveValue.hpp"

namespace fsi::structure {

void CableKind::build(const std::vector<MeshInput>& inputs, const MaterialTable& materials,
                      Model& model) const {
  for (const auto& m : materials.cable) checkMaterial(m);  // the key's range and message (model/MaterialKeys)
  model.cableMaterials = materials.cable;
  for (std::size_t m = 0; m < inputs.size(); ++m)
    if (!inputs[m].mesh.lines.empty() && inputs[m].cableMaterial < 0)
      throw MeshInputError(int(m),
                           fmt::format("mesh '{}' has lines but no cable material", inputs[m].mesh.name));
  const Nodes& N = model.nodes;
  // Sorted by material then by first node.
  struct LineRef {
    int mesh, local, material, minNode;
  };
  std::vector<LineRef> lines;
  for (std::size_t m = 0; m < inputs.size(); ++m) {
    const MeshData& md = inputs[m].mesh;
    const auto& nm = model.meshes[m].node;
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
  std::stable_sort(lines.begin(), lines.end(), [](const LineRef& a, const LineRef& b) {
    return a.material != b.material ? a.material < b.material : a.minNode < b.minNode;
  });

  Cables& C = model.cables;
  C.count = int(lines.size());
  C.conn.resize(2 * C.count);
  C.restLength.resize(C.count);
  C.invWaveSpeed.resize(C.count);
  C.tag.resize(C.count);
  C.mesh.resize(C.count);
  for (std::size_t m = 0; m < inputs.size(); ++m)
    model.meshes[m].line.assign(inputs[m].mesh.lines.size(), -1);
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
}

std::optional<CellSet> CableKind::outputCells(const Model& model) const {
  return CellSet{"cables", "lines", "Line", "Polyline", 2, model.cables.conn};
}

std::vector<std::pair<std::string, double>> CableKind::report(const Model& model, const double* x) const {
  if (model.cables.count == 0) return {};
  std::vector<double> tension;
  cableTensions(model.cables, x, tension);
  return {{"max_force", *std::max_element(tension.begin(), tension.end())}};
}

std::unique_ptr<Effect> CableKind::makeForces(const Model& model, const ElementDamping& damping) const {
  return std::make_unique<CableForces>(model.cables, damping);
}

void CableKind::addLumpedMass(const Model& model, std::vector<double>& mass) const {
  twonode::addLumpedMass(model.cables, mass);
}

double CableKind::referenceStableDt(const Model& model) const {
  return twonode::referenceStableDt(model.cables);
}

std::optional<LimitingElement> CableKind::limitingElementAt(const Model& model, int node) const {
  return twonode::limitingElementAt(model.cables, node);
}

ScaledMass CableKind::scaleMass(Model& model, double need) const {
  return twonode::scaleMass(model.cables, model.nodes.mass, need);
}

void CableKind::addStiffnessBounds(const Model& model, const double* x, std::vector<double>& dofRow,
                                   std::vector<double>& dofDiag) const {
  twonode::addStiffnessBounds<true>(model.cables, x, dofRow, dofDiag);
}

void CableKind::addFields(const Model& model, const double* x, const std::set<std::string>& wanted,
                          ElementFieldBuffers& buffers, std::vector<FieldView>& views) const {
  if (model.cables.count == 0 || !wanted.count("cable_force")) return;
  buffers.arrays.resize(1);
  cableTensions(model.cables, x, buffers.arrays[0]);
  views.push_back({"cable_force", FieldView::Center::Line, 1, buffers.arrays[0].data()});
}

}  // namespace fsi::structure
