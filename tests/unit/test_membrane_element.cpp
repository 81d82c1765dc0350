// Membrane triangle: rigid-body invariance, constant-strain patch test, internal-force consistency.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "structure/elements/BuildModel.hpp"
#include "structure/elements/MembraneForces.hpp"
#include "structure/material/WrinklingMembrane.hpp"
#include "structure/model/Model.hpp"
#include "structure/scene/Generators.hpp"

using namespace fsi::structure;

namespace {

Model plateModel(bool wrinkling, const std::string& pattern = "alternating", int n = 4) {
  RectangleParams p;
  p.size = {1.0, 0.6};
  p.divisions = {n, n};
  p.pattern = pattern;
  MeshInput in;
  in.mesh = rectangle(p, "plate");
  // Distort the interior so the patch test runs on irregular triangles.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-0.02, 0.02);
  for (auto& pt : in.mesh.points)
    if (std::abs(std::abs(pt[0]) - 0.5) > 1e-12 && std::abs(std::abs(pt[1]) - 0.3) > 1e-12)
      pt[0] += d(rng), pt[1] += d(rng);
  in.membraneMaterial = 0;
  MembraneMaterial m{"m", 2.0e9, 0.3, 1e-3, 1000, wrinkling};
  return buildModel({in}, {m}, {});
}

// Rodrigues rotation of v about unit axis k by angle a.
std::array<double, 3> rotate(const double* v, const std::array<double, 3>& k, double a) {
  const double c = std::cos(a), s = std::sin(a);
  const double kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
  const double kxv[3] = {k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2], k[0] * v[1] - k[1] * v[0]};
  std::array<double, 3> r;
  for (int i = 0; i < 3; ++i) r[i] = v[i] * c + kxv[i] * s + k[i] * kv * (1 - c);
  return r;
}

void forces(const Model& model, const MembraneForces& mf, std::vector<double>& f, double& energy) {
  f.assign(3 * model.nodes.count, 0.0);
  std::vector<double> fe(f.size(), 0.0);
  ForceContext ctx;
  ctx.x = model.nodes.x.data();
  ctx.v = model.nodes.v.data();
  ctx.fint = f.data();
  ctx.fext = fe.data();
  ctx.wantEnergy = true;
  mf.addForces(ctx);
  energy = ctx.strainEnergy;
}

}  // namespace

class RigidRotation : public ::testing::TestWithParam<double> {};

TEST_P(RigidRotation, GivesZeroStressForceAndEnergy) {
  for (bool wrinkling : {true, false}) {
    Model model = plateModel(wrinkling);
    const std::array<double, 3> axis{0.267261241912424, 0.534522483824849, 0.801783725737273};
    for (int i = 0; i < model.nodes.count; ++i) {
      const auto r = rotate(&model.nodes.X[3 * i], axis, GetParam());
      for (int k = 0; k < 3; ++k) model.nodes.x[3 * i + k] = r[k] + 10.0 * (k + 1);  // plus a translation
    }
    MembraneForces mf(model.membranes, {});
    std::vector<double> f;
    double energy = 0;
    forces(model, mf, f, energy);
    double fmax = 0;
    for (double v : f) fmax = std::max(fmax, std::abs(v));
    // A 1e-6 strain would give forces of order E t h 1e-6 ~ 0.5 N: round-off is ~1e-7 N.
    EXPECT_LT(fmax, 1e-5) << "angle " << GetParam();
    EXPECT_LT(energy, 1e-12);
    MembraneStressField s;
    mf.evaluate(model.nodes.x.data(), s);
    for (double c : s.cauchy) EXPECT_LT(std::abs(c), 1e2);  // vs 2e9 * strain
  }
}

INSTANTIATE_TEST_SUITE_P(Angles, RigidRotation,
                         ::testing::Values(1e-3, 0.5, 1.5707963267948966, 2.5, 3.14159, 5.0));

TEST(PatchTest, UniformStretchGivesUniformStressAndInteriorEquilibrium) {
  Model model = plateModel(false);
  // Homogeneous in-plane deformation x = F X with F = [[1.02, 0.01], [0.005, 0.99]] (taut and sheared).
  const double F[2][2] = {{1.02, 0.01}, {0.005, 0.99}};
  for (int i = 0; i < model.nodes.count; ++i) {
    const double X = model.nodes.X[3 * i], Y = model.nodes.X[3 * i + 1];
    model.nodes.x[3 * i] = F[0][0] * X + F[0][1] * Y;
    model.nodes.x[3 * i + 1] = F[1][0] * X + F[1][1] * Y;
    model.nodes.x[3 * i + 2] = 0.0;
  }
  // Exact Green–Lagrange strain and second Piola–Kirchhoff stress.
  const double C11 = F[0][0] * F[0][0] + F[1][0] * F[1][0];
  const double C22 = F[0][1] * F[0][1] + F[1][1] * F[1][1];
  const double C12 = F[0][0] * F[0][1] + F[1][0] * F[1][1];
  const double E11 = 0.5 * (C11 - 1), E22 = 0.5 * (C22 - 1), E12 = 0.5 * C12;
  const double Y = 2.0e9, nu = 0.3, c11 = Y / (1 - nu * nu);
  const double S11 = c11 * (E11 + nu * E22), S22 = c11 * (E22 + nu * E11), S12 = c11 * (1 - nu) * E12;
  // Cauchy σ = F S Fᵀ / det F.
  const double J = F[0][0] * F[1][1] - F[0][1] * F[1][0];
  const double P[2][2] = {{F[0][0] * S11 + F[0][1] * S12, F[0][0] * S12 + F[0][1] * S22},
                          {F[1][0] * S11 + F[1][1] * S12, F[1][0] * S12 + F[1][1] * S22}};
  const double sxx = (P[0][0] * F[0][0] + P[0][1] * F[0][1]) / J;
  const double syy = (P[1][0] * F[1][0] + P[1][1] * F[1][1]) / J;
  const double sxy = (P[0][0] * F[1][0] + P[0][1] * F[1][1]) / J;

  MembraneForces mf(model.membranes, {});
  MembraneStressField s;
  mf.evaluate(model.nodes.x.data(), s);
  for (int e = 0; e < model.membranes.count; ++e) {
    EXPECT_NEAR(s.cauchy[6 * e + 0], sxx, 1e-8 * std::abs(sxx)) << e;
    EXPECT_NEAR(s.cauchy[6 * e + 1], syy, 1e-8 * std::abs(sxx)) << e;
    EXPECT_NEAR(s.cauchy[6 * e + 3], sxy, 1e-8 * std::abs(sxx)) << e;
    EXPECT_EQ(s.state[e], 0.0);
  }
  std::vector<double> f;
  double energy = 0;
  forces(model, mf, f, energy);
  // Interior nodes are in equilibrium; the boundary carries the traction.
  const auto& bnd = model.meshes[0].source.nodeGroups.at("boundary");
  std::vector<bool> onBoundary(model.nodes.count, false);
  for (int i : bnd) onBoundary[model.meshes[0].node[i]] = true;
  const double scale = std::abs(sxx) * 1e-3 * 0.15;  // stress x thickness x element size
  for (int i = 0; i < model.nodes.count; ++i) {
    if (onBoundary[i]) continue;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(f[3 * i + k], 0.0, 1e-9 * scale) << "node " << i;
  }
  // Strain energy = W(E) times the reference volume 1.0 * 0.6 * 1e-3.
  const double W = 0.5 * (S11 * E11 + S22 * E22 + 2 * S12 * E12);
  EXPECT_NEAR(energy, W * 0.6e-3, 1e-10 * W);
}

TEST(MembraneForces, AreTheGradientOfTheStrainEnergy) {
  // Central finite differences of the strain energy against the kernel's forces, in a wrinkled state.
  Model model = plateModel(true, "cross", 2);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> d(-0.01, 0.03);
  // Stretch along x, squeeze along y (tension field), plus a random out-of-plane and in-plane shake.
  for (int i = 0; i < model.nodes.count; ++i) {
    model.nodes.x[3 * i] = model.nodes.X[3 * i] * 1.01 + d(rng) * 0.02;
    model.nodes.x[3 * i + 1] = model.nodes.X[3 * i + 1] * 0.99 + d(rng) * 0.02;
    model.nodes.x[3 * i + 2] = d(rng) * 0.1;
  }
  MembraneForces mf(model.membranes, {});
  std::vector<double> f, tmp;
  double e0 = 0;
  forces(model, mf, f, e0);
  MembraneStressField s;
  mf.evaluate(model.nodes.x.data(), s);
  int wrinkled = 0;
  for (double st : s.state) wrinkled += st == 1.0;
  ASSERT_GT(wrinkled, 0) << "the perturbed state should contain wrinkled elements";
  const double h = 1e-7;
  for (int dof = 0; dof < 3 * model.nodes.count; dof += 2) {
    double ep, em;
    model.nodes.x[dof] += h;
    forces(model, mf, tmp, ep);
    model.nodes.x[dof] -= 2 * h;
    forces(model, mf, tmp, em);
    model.nodes.x[dof] += h;
    const double fd = (ep - em) / (2 * h);
    EXPECT_NEAR(f[dof], fd, 1e-5 * (std::abs(fd) + 1.0)) << "dof " << dof;
  }
}
