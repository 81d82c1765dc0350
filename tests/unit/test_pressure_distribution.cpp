// A pressure that varies over a surface: the resultant of a linear Cp(x/c) on a flat plate equals the
// integral q ∫ Cp dx · span (exact for a table linear in x on any triangulation, by the centroid rule), and
// its moment about the leading edge equals q ∫ Cp x dx · span within the centroid rule's error, which falls
// at second order with the mesh.
#include <gtest/gtest.h>

#include <cmath>

#include "structure/effects/PressureDistribution.hpp"
#include "structure/scene/Generators.hpp"

using namespace fsi::structure;

namespace {

struct Result {
  double force = 0, moment = 0;
};

// Plate 1 m chord (x) by 2 m span (y), normal +z, under Cp(x) = 1 − x (a table with two points), q = 50 Pa.
Result plate(int n) {
  RectangleParams rp;
  rp.size = {1.0, 2.0};
  rp.divisions = {n, 2 * n};
  rp.center = {0.5, 0.0, 0.0};
  rp.pattern = "alternating";
  const MeshData m = rectangle(rp);
  std::vector<double> X;
  for (const auto& p : m.points) X.insert(X.end(), p.begin(), p.end());
  std::vector<int> conn;
  for (const auto& t : m.triangles) conn.insert(conn.end(), t.begin(), t.end());
  const CpTable cp{{0.0, 1.0}, {1.0, 0.0}};
  const auto values = chordwisePressure(X, conn, cp, 50.0, {0, 0, 0}, {1, 0, 0}, 1.0);
  PressureDistribution effect("plate", conn, values, TimeFunction::constant());
  std::vector<double> f(X.size(), 0.0), fint(X.size(), 0.0);
  ForceContext ctx;
  ctx.x = X.data();
  ctx.fint = fint.data();
  ctx.fext = f.data();
  effect.addForces(ctx);
  Result r;
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    r.force += f[3 * i + 2];
    r.moment += f[3 * i + 2] * X[3 * i];
  }
  return r;
}

}  // namespace

TEST(PressureDistribution, ResultantAndMomentOfALinearCp) {
  const double q = 50.0, span = 2.0;
  const double force = q * 0.5 * span;           // q ∫0^1 (1 − x) dx · b
  const double moment = q * (1.0 / 6.0) * span;  // q ∫0^1 (1 − x) x dx · b
  const Result coarse = plate(4), fine = plate(8);
  EXPECT_NEAR(coarse.force, force, force * 1e-12);
  EXPECT_NEAR(fine.force, force, force * 1e-12);
  const double eCoarse = std::abs(coarse.moment - moment), eFine = std::abs(fine.moment - moment);
  EXPECT_LT(eFine, 0.01 * moment);
  EXPECT_LT(eFine, eCoarse / 3.0);
}

TEST(PressureDistribution, TableIsPiecewiseLinearAndConstantOutside) {
  const CpTable t{{0.0, 0.1, 1.0}, {-1.0, -2.0, 0.0}};
  EXPECT_DOUBLE_EQ(t.at(-0.5), -1.0);
  EXPECT_DOUBLE_EQ(t.at(0.05), -1.5);
  EXPECT_DOUBLE_EQ(t.at(0.55), -1.0);
  EXPECT_DOUBLE_EQ(t.at(2.0), 0.0);
}

TEST(PressureDistribution, DeadLoadKeepsItsDirectionWhenTheSurfaceTurns) {
  // One triangle in the x-y plane (normal +z) under p = 60 Pa, then turned rigidly by 90° about x (normal
  // −y): the follower force turns with it, the dead load keeps the reference force (0, 0, p A).
  const std::vector<double> X{0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::vector<double> turned{0, 0, 0, 1, 0, 0, 0, 0, 1};
  const std::vector<int> conn{0, 1, 2};
  const PressureDistribution follower("t", conn, {60.0}, TimeFunction::constant());
  const PressureDistribution dead =
      PressureDistribution::dead("t", conn, {60.0}, TimeFunction::constant(), X);
  auto total = [&](const PressureDistribution& e, const std::vector<double>& x) {
    std::vector<double> f(9, 0.0), fint(9, 0.0);
    ForceContext ctx;
    ctx.x = x.data();
    ctx.fint = fint.data();
    ctx.fext = f.data();
    e.addForces(ctx);
    return std::array<double, 3>{f[0] + f[3] + f[6], f[1] + f[4] + f[7], f[2] + f[5] + f[8]};
  };
  const double pA = 60.0 * 0.5;
  EXPECT_NEAR(total(follower, X)[2], pA, 1e-12);
  EXPECT_NEAR(total(dead, X)[2], pA, 1e-12);
  EXPECT_NEAR(total(follower, turned)[1], -pA, 1e-12);  // normal (1,0,0)×(0,0,1) = (0,−1,0)
  EXPECT_NEAR(total(dead, turned)[2], pA, 1e-12);
  EXPECT_NEAR(total(dead, turned)[1], 0.0, 1e-12);
  EXPECT_TRUE(follower.follower());
  EXPECT_FALSE(dead.follower());
}
