#include "structure/integrate/FictitiousMass.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "structure/model/Error.hpp"

namespace fsi::structure {

namespace {
// The scene names of the rules, the one place they are spelled (`solver: {mass: NAME}`).
const std::vector<std::pair<FictitiousMassRule, std::string>>& ruleNames() {
  static const std::vector<std::pair<FictitiousMassRule, std::string>> names{
      {FictitiousMassRule::Gerschgorin, "gerschgorin"},
      {FictitiousMassRule::StressBound, "stress"},
      {FictitiousMassRule::RezaiePajand, "rezaiee_pajand"}};
  return names;
}
}  // namespace

const std::vector<std::string>& fictitiousMassRuleNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& entry : ruleNames()) n.push_back(entry.second);
    return n;
  }();
  return names;
}

FictitiousMassRule fictitiousMassRuleFromName(const std::string& name) {
  for (const auto& [rule, text] : ruleNames())
    if (text == name) return rule;
  std::string valid;
  for (const std::string& n : fictitiousMassRuleNames()) valid += (valid.empty() ? "" : ", ") + n;
  throw InputError("unknown fictitious mass rule '" + name + "'; valid: " + valid);
}

std::string toString(FictitiousMassRule rule) {
  for (const auto& [r, text] : ruleNames())
    if (r == rule) return text;
  return "?";
}

namespace {

// Reference gradients and F (3x2) of one triangle, as in the force kernel.
struct TriangleState {
  double G[3][2];  // ∇N_a on the reference triangle
  double F[3][2];  // F_iI
  double S[3];     // S11, S22, S12 (taut law)
  double tA0;
};

TriangleState triangleState(const MembraneTriangles& T, const MembraneBlock& b, const double* x, int e) {
  TriangleState s{};
  const double* g = &T.geo[MembraneTriangles::kGeo * e];
  const double n2x = g[0], n2y = -g[1] * g[0] * g[2], n3y = g[2];
  s.G[1][0] = n2x, s.G[1][1] = n2y;
  s.G[2][0] = 0.0, s.G[2][1] = n3y;
  s.G[0][0] = -n2x, s.G[0][1] = -n2y - n3y;
  s.tA0 = g[3];
  const int* n = &T.conn[3 * e];
  for (int i = 0; i < 3; ++i)
    for (int I = 0; I < 2; ++I) {
      double v = 0;
      for (int a = 0; a < 3; ++a) v += x[3 * n[a] + i] * s.G[a][I];
      s.F[i][I] = v;
    }
  double C[2][2];
  for (int I = 0; I < 2; ++I)
    for (int J = 0; J < 2; ++J)
      C[I][J] = s.F[0][I] * s.F[0][J] + s.F[1][I] * s.F[1][J] + s.F[2][I] * s.F[2][J];
  const double e11 = 0.5 * (C[0][0] - 1), e22 = 0.5 * (C[1][1] - 1), g12 = C[0][1];
  s.S[0] = b.c11 * (e11 + b.poisson * e22);
  s.S[1] = b.c11 * (e22 + b.poisson * e11);
  s.S[2] = 0.5 * b.c11 * (1 - b.poisson) * g12;
  if (b.wrinkling) {  // geometric stiffness only from tension: a slack or wrinkled direction adds nothing
    const double m = 0.5 * (s.S[0] + s.S[1]);
    const double r = std::sqrt(0.25 * (s.S[0] - s.S[1]) * (s.S[0] - s.S[1]) + s.S[2] * s.S[2]);
    if (m + r <= 0) s.S[0] = s.S[1] = s.S[2] = 0;
  }
  return s;
}

}  // namespace

namespace {
// Per-dof row sums and diagonal of the tangent stiffness, assembled element by element.
void tangentStiffnessDofBounds(const Model& model, const double* x, std::vector<double>& dofRow,
                               std::vector<double>& dofDiag) {
  const int N = model.nodes.count;
  dofRow.assign(3 * N, 0.0);
  dofDiag.assign(3 * N, 0.0);
  const MembraneTriangles& T = model.membranes;
  for (const MembraneBlock& b : T.blocks) {
    const double D[3][3] = {
        {b.c11, b.c11 * b.poisson, 0}, {b.c11 * b.poisson, b.c11, 0}, {0, 0, 0.5 * b.c11 * (1 - b.poisson)}};
    for (int e = b.begin; e < b.end; ++e) {
      const TriangleState s = triangleState(T, b, x, e);
      // B_a (Voigt 11, 22, 2·12 by dof i): strain variation per unit motion of node a along i.
      double B[3][3][3];  // [a][voigt][i]
      for (int a = 0; a < 3; ++a)
        for (int i = 0; i < 3; ++i) {
          B[a][0][i] = s.F[i][0] * s.G[a][0];
          B[a][1][i] = s.F[i][1] * s.G[a][1];
          B[a][2][i] = s.F[i][0] * s.G[a][1] + s.F[i][1] * s.G[a][0];
        }
      const int* n = &T.conn[3 * e];
      for (int a = 0; a < 3; ++a)
        for (int i = 0; i < 3; ++i) {
          double row = 0;
          for (int c = 0; c < 3; ++c) {
            const double geom = s.G[a][0] * (s.S[0] * s.G[c][0] + s.S[2] * s.G[c][1]) +
                                s.G[a][1] * (s.S[2] * s.G[c][0] + s.S[1] * s.G[c][1]);
            for (int k = 0; k < 3; ++k) {
              double mat = 0;
              for (int p = 0; p < 3; ++p)
                for (int q = 0; q < 3; ++q) mat += B[a][p][i] * D[p][q] * B[c][q][k];
              const double K = s.tA0 * (mat + (i == k ? geom : 0.0));
              row += std::abs(K);
              if (a == c && i == k) dofDiag[3 * n[a] + i] += K;
            }
          }
          dofRow[3 * n[a] + i] += row;
        }
    }
  }
  const Cables& C = model.cables;
  for (const CableBlock& b : C.blocks)
    for (int e = b.begin; e < b.end; ++e) {
      const int i = C.conn[2 * e], j = C.conn[2 * e + 1];
      double d[3], L = 0;
      for (int k = 0; k < 3; ++k) d[k] = x[3 * j + k] - x[3 * i + k], L += d[k] * d[k];
      L = std::sqrt(L);
      const double L0 = C.restLength[e];
      const double T0 = b.axialStiffness * std::max(0.0, (L - L0) / L0);
      const double ka = b.axialStiffness / L0, kg = T0 / L;
      for (int k = 0; k < 3; ++k) {
        // K = ka e⊗e + kg (I − e⊗e) on the 2x2 node blocks [K −K; −K K]
        double row = 0;
        for (int l = 0; l < 3; ++l) {
          const double el = d[k] * d[l] / (L * L);
          row += 2.0 * std::abs(ka * el + kg * ((k == l ? 1.0 : 0.0) - el));
        }
        const double diag = ka * d[k] * d[k] / (L * L) + kg * (1.0 - d[k] * d[k] / (L * L));
        dofRow[3 * i + k] += row, dofRow[3 * j + k] += row;
        dofDiag[3 * i + k] += diag, dofDiag[3 * j + k] += diag;
      }
    }
}

}  // namespace

void tangentStiffnessBounds(const Model& model, const double* x, std::vector<double>& rowSum,
                            std::vector<double>& diagonal) {
  const int N = model.nodes.count;
  std::vector<double> dofRow, dofDiag;
  tangentStiffnessDofBounds(model, x, dofRow, dofDiag);
  rowSum.assign(N, 0.0);
  diagonal.assign(N, 0.0);
  for (int i = 0; i < N; ++i)
    for (int k = 0; k < 3; ++k) {
      rowSum[i] = std::max(rowSum[i], dofRow[3 * i + k]);
      diagonal[i] = std::max(diagonal[i], dofDiag[3 * i + k]);
    }
}

std::vector<double> fictitiousMasses(const Model& model, const double* x, FictitiousMassRule rule,
                                     double lambda) {
  const int N = model.nodes.count;
  std::vector<double> m(N, 0.0);
  if (rule == FictitiousMassRule::StressBound) {
    const MembraneTriangles& T = model.membranes;
    for (const MembraneBlock& b : T.blocks) {
      const double K = b.young / (3.0 * (1.0 - 2.0 * b.poisson)), G = b.young / (2.0 * (1.0 + b.poisson));
      const MembraneMaterial& mat = model.membraneMaterials[b.material];
      for (int e = b.begin; e < b.end; ++e) {
        const TriangleState s = triangleState(T, b, x, e);
        const double tr = s.S[0] + s.S[1];
        const double vm =
            std::sqrt(s.S[0] * s.S[0] - s.S[0] * s.S[1] + s.S[1] * s.S[1] + 3 * s.S[2] * s.S[2]);
        const double k = 0.25 * mat.thickness * (K + G + tr / 3.0 + 0.5 * vm);
        for (int a = 0; a < 3; ++a) m[T.conn[3 * e + a]] += 0.5 * lambda * k;
      }
    }
    // Cables (not covered by the proposal) keep the Gerschgorin bound.
    if (model.cables.count > 0) {
      std::vector<double> row, diag;
      tangentStiffnessBounds(model, x, row, diag);
      std::vector<char> onMembrane(N, 0);
      for (int c : T.conn) onMembrane[c] = 1;
      for (int i = 0; i < N; ++i)
        if (!onMembrane[i]) m[i] = 0.5 * lambda * row[i];
    }
    return m;
  }
  std::vector<double> row, diag;
  tangentStiffnessBounds(model, x, row, diag);
  for (int i = 0; i < N; ++i)
    m[i] = rule == FictitiousMassRule::Gerschgorin ? 0.5 * lambda * row[i]
                                                   : lambda * std::max(diag[i], 0.5 * row[i]);
  return m;
}

}  // namespace fsi::structure
