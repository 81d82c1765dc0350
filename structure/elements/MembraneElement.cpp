#include "structure/elements/MembraneElement.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "structure/elements/MembraneForces.hpp"
#include "structure/elements/MembraneKinematics.hpp"
#include "structure/model/Error.hpp"
#include "structure/model/MaterialKeys.hpp"
#include "structure/model/PositiveValue.hpp"

namespace fsi::structure {

namespace {

// The materials' ranges and messages are their keys' (model/MaterialKeys): the scene reader checks the same
// entries, located at the key; this guards a Model built from materials made in code.
void checkMaterials(const std::vector<MembraneMaterial>& mm) {
  for (const auto& m : mm) checkMaterial(m);
}

}  // namespace

void MembraneKind::build(const std::vector<MeshInput>& inputs, const MaterialTable& materials,
                         Model& model) const {
  checkMaterials(materials.membrane);
  model.membraneMaterials = materials.membrane;
  for (std::size_t m = 0; m < inputs.size(); ++m)
    if (!inputs[m].mesh.triangles.empty() && inputs[m].membraneMaterial < 0)
      throw MeshInputError(
          int(m), fmt::format("mesh '{}' has triangles but no membrane material", inputs[m].mesh.name));
  const Nodes& N = model.nodes;
  // Sorted by material then by first node.
  struct TriRef {
    int mesh, local, material, minNode;
  };
  std::vector<TriRef> tris;
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
  }
  std::stable_sort(tris.begin(), tris.end(), [](const TriRef& a, const TriRef& b) {
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
  for (std::size_t m = 0; m < inputs.size(); ++m)
    model.meshes[m].triangle.assign(inputs[m].mesh.triangles.size(), -1);
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
}

std::optional<CellSet> MembraneKind::outputCells(const Model& model) const {
  return CellSet{"membranes", "triangles", "Triangle", "Triangle", 3, model.membranes.conn};
}

std::vector<std::pair<std::string, double>> MembraneKind::report(const Model& model, const double* x) const {
  if (model.membranes.count == 0) return {};
  MembraneStressField f;
  membraneStresses(model.membranes, x, f);
  double major = -std::numeric_limits<double>::infinity();
  for (int e = 0; e < model.membranes.count; ++e) major = std::max(major, f.principal[2 * std::size_t(e)]);
  return {{"max_principal_stress", major}};
}

std::unique_ptr<Effect> MembraneKind::makeForces(const Model& model, const ElementDamping& damping) const {
  return std::make_unique<MembraneForces>(model.membranes, damping);
}

void MembraneKind::addLumpedMass(const Model& model, std::vector<double>& mass) const {
  const MembraneTriangles& T = model.membranes;
  for (const MembraneBlock& b : T.blocks)
    for (int e = b.begin; e < b.end; ++e) {
      const double m = b.density * T.geo[MembraneTriangles::kGeo * e + 3] / 3.0;  // geo[3] = t A0
      for (int k = 0; k < 3; ++k) mass[T.conn[3 * e + k]] += m;
    }
}

double MembraneKind::referenceStableDt(const Model& model) const {
  double dt = std::numeric_limits<double>::infinity();
  const MembraneTriangles& T = model.membranes;
  for (int e = 0; e < T.count; ++e) dt = std::min(dt, std::sqrt(T.refStep2[e]));  // smallest altitude / c
  return dt;
}

ScaledMass MembraneKind::scaleMass(Model& model, double need) const {
  ScaledMass r;
  MembraneTriangles& T = model.membranes;
  std::vector<double>& mass = model.nodes.mass;
  for (const MembraneBlock& b : T.blocks)
    for (int e = b.begin; e < b.end; ++e) {
      const double* g = &T.geo[MembraneTriangles::kGeo * e];
      const double dt = std::sqrt(T.refStep2[e]);
      if (dt >= need) continue;
      const double s = (need / dt) * (need / dt);               // c ∝ ρ^-1/2
      const double extra = (s - 1.0) * b.density * g[3] / 3.0;  // g[3] = t A0
      for (int k = 0; k < 3; ++k) mass[T.conn[3 * e + k]] += extra;
      r.added += 3.0 * extra;
      T.invWaveSpeed[e] *= std::sqrt(s);
      T.refStep2[e] *= s;
      ++r.elements;
    }
  return r;
}

namespace {

// The stress the stiffness bounds use: the taut law (its tangent bounds the wrinkling one), with the
// geometric stiffness only from tension where the material wrinkles (a slack or wrinkled direction adds
// nothing).
void boundStress(const membrane::Kinematics& k, const MembraneBlock& b, double S[3]) {
  membrane::tautStress(k, b, S);
  if (b.wrinkling) {
    const double m = 0.5 * (S[0] + S[1]);
    const double r = std::sqrt(0.25 * (S[0] - S[1]) * (S[0] - S[1]) + S[2] * S[2]);
    if (m + r <= 0) S[0] = S[1] = S[2] = 0;
  }
}

}  // namespace

void MembraneKind::addStiffnessBounds(const Model& model, const double* x, std::vector<double>& dofRow,
                                      std::vector<double>& dofDiag) const {
  const MembraneTriangles& T = model.membranes;
  for (const MembraneBlock& b : T.blocks) {
    const double D[3][3] = {
        {b.c11, b.c11 * b.poisson, 0}, {b.c11 * b.poisson, b.c11, 0}, {0, 0, 0.5 * b.c11 * (1 - b.poisson)}};
    for (int e = b.begin; e < b.end; ++e) {
      const int* n = &T.conn[3 * e];
      membrane::Kinematics k;
      membrane::kinematics(x, n, &T.geo[MembraneTriangles::kGeo * e], k);
      double G[3][2], S[3];
      membrane::shapeGradients(k, G);
      boundStress(k, b, S);
      const double F[3][2] = {{k.f1[0], k.f2[0]}, {k.f1[1], k.f2[1]}, {k.f1[2], k.f2[2]}};
      // B_a (Voigt 11, 22, 2·12 by dof i): strain variation per unit motion of node a along i.
      double B[3][3][3];  // [a][voigt][i]
      for (int a = 0; a < 3; ++a)
        for (int i = 0; i < 3; ++i) {
          B[a][0][i] = F[i][0] * G[a][0];
          B[a][1][i] = F[i][1] * G[a][1];
          B[a][2][i] = F[i][0] * G[a][1] + F[i][1] * G[a][0];
        }
      for (int a = 0; a < 3; ++a)
        for (int i = 0; i < 3; ++i) {
          double row = 0;
          for (int c = 0; c < 3; ++c) {
            const double geom =
                G[a][0] * (S[0] * G[c][0] + S[2] * G[c][1]) + G[a][1] * (S[2] * G[c][0] + S[1] * G[c][1]);
            for (int kk = 0; kk < 3; ++kk) {
              double mat = 0;
              for (int p = 0; p < 3; ++p)
                for (int q = 0; q < 3; ++q) mat += B[a][p][i] * D[p][q] * B[c][q][kk];
              const double K = k.tA0 * (mat + (i == kk ? geom : 0.0));
              row += std::abs(K);
              if (a == c && i == kk) dofDiag[3 * n[a] + i] += K;
            }
          }
          dofRow[3 * n[a] + i] += row;
        }
    }
  }
}

void MembraneKind::addStressBoundMass(const Model& model, const double* x, double lambda,
                                      std::vector<double>& m, std::vector<char>& covered) const {
  const MembraneTriangles& T = model.membranes;
  for (const MembraneBlock& b : T.blocks) {
    const double K = b.young / (3.0 * (1.0 - 2.0 * b.poisson)), G = b.young / (2.0 * (1.0 + b.poisson));
    const double thickness = model.membraneMaterials[b.material].thickness;
    for (int e = b.begin; e < b.end; ++e) {
      membrane::Kinematics k;
      membrane::kinematics(x, &T.conn[3 * e], &T.geo[MembraneTriangles::kGeo * e], k);
      double S[3];
      boundStress(k, b, S);
      const double tr = S[0] + S[1];
      const double vm = std::sqrt(S[0] * S[0] - S[0] * S[1] + S[1] * S[1] + 3 * S[2] * S[2]);
      const double kb = 0.25 * thickness * (K + G + tr / 3.0 + 0.5 * vm);
      for (int a = 0; a < 3; ++a) {
        m[T.conn[3 * e + a]] += 0.5 * lambda * kb;
        covered[T.conn[3 * e + a]] = 1;
      }
    }
  }
}

void MembraneKind::addFields(const Model& model, const double* x, const std::set<std::string>& wanted,
                             ElementFieldBuffers& buffers, std::vector<FieldView>& views) const {
  const bool stress = wanted.count("stress") > 0, principal = wanted.count("principal_stress") > 0,
             state = wanted.count("wrinkle_state") > 0;
  if (model.membranes.count == 0 || !(stress || principal || state)) return;
  // The buffers' vectors are moved in and out: no allocation once they have their size.
  auto& a = buffers.arrays;
  a.resize(6);
  MembraneStressField f;
  f.cauchy = std::move(a[0]), f.principal = std::move(a[1]), f.state = std::move(a[2]);
  f.majorStrain = std::move(a[3]);
  membraneStresses(model.membranes, x, f);
  a[0] = std::move(f.cauchy), a[1] = std::move(f.principal), a[2] = std::move(f.state);
  a[3] = std::move(f.majorStrain);
  const int ne = model.membranes.count;
  a[4].resize(ne), a[5].resize(ne);
  for (int e = 0; e < ne; ++e) a[4][e] = a[1][2 * e], a[5][e] = a[1][2 * e + 1];
  if (stress) views.push_back({"stress", FieldView::Center::Triangle, 6, a[0].data()});
  if (principal) {
    views.push_back({"principal_stress_major", FieldView::Center::Triangle, 1, a[4].data()});
    views.push_back({"principal_stress_minor", FieldView::Center::Triangle, 1, a[5].data()});
  }
  if (state) views.push_back({"wrinkle_state", FieldView::Center::Triangle, 1, a[2].data()});
}

std::optional<StrainedElement> MembraneKind::mostStrained(const Model& model, const double* x) const {
  MembraneStressField f;
  membraneStresses(model.membranes, x, f);
  StrainedElement worst;
  double worstStrain = -1;
  for (int e = 0; e < model.membranes.count; ++e) {
    const double es = f.majorStrain[e];
    if (!std::isfinite(es)) return StrainedElement{e, es};
    if (es > worstStrain) worstStrain = es, worst = {e, es};
  }
  if (worst.element < 0) return std::nullopt;
  return worst;
}

}  // namespace fsi::structure
