#include "structure/elements/MembraneElement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "structure/elements/MembraneForces.hpp"
#include "structure/elements/MembraneKinematics.hpp"
#include "structure/scene/ReadMaterials.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure {

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

void MembraneKind::readMeshKeys(const YamlMap& entry, const MaterialTable& materials, MeshInput& in) const {
  if (entry.has("material"))
    in.membraneMaterial = materialRef(entry, "material", materialsOfKind(materials, "membrane"), "membrane");
}

void MembraneKind::checkMeshInput(const YamlMap& entry, const MeshInput& in) const {
  if (!in.mesh.triangles.empty() && in.membraneMaterial < 0)
    entry.fail("this mesh has triangles: give it a membrane 'material'");
}

}  // namespace fsi::structure
