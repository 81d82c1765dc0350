#include "structure/elements/BarElement.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <any>
#include <cmath>
#include <limits>

#include "structure/elements/BarForces.hpp"
#include "structure/elements/TwoNodeElements.hpp"
#include "structure/model/Error.hpp"
#include "structure/model/PositiveValue.hpp"

namespace fsi::structure {

const Bars& barsOf(const Model& model) {
  static const Bars none;
  const Bars* B = model.block<Bars>("bar");
  return B ? *B : none;
}

std::string BarKind::describe(const Model& model, int element) const {
  const Bars& B = barsOf(model);
  return fmt::format("bar {} of mesh '{}'", B.tag[element], model.meshes[B.mesh[element]].name);
}

namespace {

// The bar materials of the table (the scene's `type: bar` entries), checked.
std::vector<BarMaterial> barMaterials(const MaterialTable& table) {
  std::vector<BarMaterial> out;
  const auto it = table.other.find("bar");
  if (it == table.other.end()) return out;
  for (const KindMaterial& m : it->second) {
    BarMaterial b;
    b.name = m.name;
    const auto value = [&](const char* key) {
      const auto v = m.values.find(key);
      const double x = v == m.values.end() ? 0.0 : v->second;
      if (!isPositiveNormal(x))
        throw InputError(fmt::format("material '{}': {} {}", m.name, key, kPositiveRule));
      return x;
    };
    b.young = value("young");
    b.area = value("area");
    b.density = value("density");
    out.push_back(b);
  }
  return out;
}

}  // namespace

void BarKind::build(const std::vector<MeshInput>& inputs, const MaterialTable& materials,
                    Model& model) const {
  Bars B;
  B.materials = barMaterials(materials);
  struct BarRef {
    int mesh, local, material, minNode;
  };
  std::vector<BarRef> refs;
  std::vector<const BarInput*> given(inputs.size(), nullptr);
  for (std::size_t m = 0; m < inputs.size(); ++m) {
    const auto it = inputs[m].kindInputs.find(name());
    if (it == inputs[m].kindInputs.end()) continue;
    const BarInput& in = std::any_cast<const BarInput&>(it->second);
    given[m] = &in;
    const MeshData& md = inputs[m].mesh;
    if (!in.lines.empty() && (in.material < 0 || in.material >= int(B.materials.size())))
      throw InputError(fmt::format("mesh '{}' has bars but no bar material", md.name));
    const auto& nm = model.meshes[m].node;
    for (std::size_t e = 0; e < in.lines.size(); ++e) {
      const auto& l = in.lines[e];
      for (int k = 0; k < 2; ++k)
        if (l[k] < 0 || l[k] >= int(md.points.size()))
          throw InputError(fmt::format("mesh '{}': bar {} refers to node index {} out of range", md.name,
                                       e < in.tags.size() ? in.tags[e] : long(e + 1), l[k]));
      refs.push_back({int(m), int(e), in.material, std::min(nm[l[0]], nm[l[1]])});
    }
  }
  std::stable_sort(refs.begin(), refs.end(), [](const BarRef& a, const BarRef& b) {
    return a.material != b.material ? a.material < b.material : a.minNode < b.minNode;
  });
  const Nodes& N = model.nodes;
  B.count = int(refs.size());
  for (int e = 0; e < B.count; ++e) {
    const BarRef& r = refs[std::size_t(e)];
    const BarInput& in = *given[std::size_t(r.mesh)];
    const auto local = std::size_t(r.local);
    B.tag.push_back(local < in.tags.size() ? in.tags[local] : long(local + 1));
    B.mesh.push_back(r.mesh);
    const int a = model.meshes[r.mesh].node[in.lines[local][0]];
    const int b = model.meshes[r.mesh].node[in.lines[local][1]];
    B.conn.push_back(a);
    B.conn.push_back(b);
    double L = 0;
    for (int k = 0; k < 3; ++k) L += (N.X[3 * b + k] - N.X[3 * a + k]) * (N.X[3 * b + k] - N.X[3 * a + k]);
    L = std::sqrt(L);
    const std::string what = fmt::format("bar {} of mesh '{}'", B.tag.back(), model.meshes[r.mesh].name);
    if (a == b || !(L > 0))
      throw InputError(fmt::format("{} has zero length (nodes {} and {})", what, N.tag[a], N.tag[b]));
    if (local < in.restLength.size() && in.restLength[local] != 0.0) {
      L = in.restLength[local];
      if (!(std::isfinite(L) && L > 0))
        throw InputError(fmt::format("{} has rest length {} (must be positive and finite)", what, L));
    }
    const BarMaterial& mat = B.materials[std::size_t(r.material)];
    B.restLength.push_back(L);
    B.invWaveSpeed.push_back(std::sqrt(mat.density / mat.young));
    if (B.blocks.empty() || B.blocks.back().material != r.material)
      B.blocks.push_back({e, e, r.material, mat.young * mat.area, mat.area, mat.density});
    B.blocks.back().end = e + 1;
  }
  model.kindBlocks[name()] = std::move(B);
}

std::unique_ptr<Effect> BarKind::makeForces(const Model& model, const ElementDamping& damping) const {
  return std::make_unique<BarForces>(barsOf(model), damping);
}

void BarKind::addLumpedMass(const Model& model, std::vector<double>& mass) const {
  twonode::addLumpedMass(barsOf(model), mass);
}

double BarKind::referenceStableDt(const Model& model) const {
  return twonode::referenceStableDt(barsOf(model));
}

std::optional<LimitingElement> BarKind::limitingElementAt(const Model& model, int node) const {
  return twonode::limitingElementAt(barsOf(model), node);
}

ScaledMass BarKind::scaleMass(Model& model, double need) const {
  Bars* B = model.block<Bars>(name());
  return B ? twonode::scaleMass(*B, model.nodes.mass, need) : ScaledMass{};
}

void BarKind::addStiffnessBounds(const Model& model, const double* x, std::vector<double>& dofRow,
                                 std::vector<double>& dofDiag) const {
  twonode::addStiffnessBounds<false>(barsOf(model), x, dofRow, dofDiag);
}

std::optional<CellSet> BarKind::outputCells(const Model& model) const {
  const Bars& B = barsOf(model);
  if (B.count == 0) return std::nullopt;
  return CellSet{"bars", "bars", "Bar", "Polyline", 2, B.conn};
}

void BarKind::addFields(const Model& model, const double* x, const std::set<std::string>& wanted,
                        ElementFieldBuffers& buffers, std::vector<FieldView>& views) const {
  const Bars& B = barsOf(model);
  const bool force = wanted.count("bar_force") > 0, strain = wanted.count("bar_strain") > 0;
  if (B.count == 0 || !(force || strain)) return;
  buffers.arrays.resize(2);
  barForces(B, x, buffers.arrays[0], buffers.arrays[1]);
  const std::size_t n = std::size_t(B.count);
  if (force) views.push_back({"bar_force", FieldView::Center::Cell, 1, buffers.arrays[0].data(), n, "Bar"});
  if (strain) views.push_back({"bar_strain", FieldView::Center::Cell, 1, buffers.arrays[1].data(), n, "Bar"});
}

std::vector<std::pair<std::string, double>> BarKind::report(const Model& model, const double* x) const {
  const Bars& B = barsOf(model);
  if (B.count == 0) return {};
  std::vector<double> force, strain;
  barForces(B, x, force, strain);
  return {{"max_force", *std::max_element(force.begin(), force.end())},
          {"min_force", *std::min_element(force.begin(), force.end())}};
}

std::optional<StrainedElement> BarKind::mostStrained(const Model& model, const double* x) const {
  const Bars& B = barsOf(model);
  if (B.count == 0) return std::nullopt;
  std::vector<double> force, strain;
  barForces(B, x, force, strain);
  StrainedElement worst;
  for (int e = 0; e < B.count; ++e) {
    const double s = strain[std::size_t(e)];
    if (!std::isfinite(s)) return StrainedElement{e, s};
    if (worst.element < 0 || std::abs(s) > std::abs(worst.strain)) worst = {e, s};
  }
  return worst;
}

}  // namespace fsi::structure
