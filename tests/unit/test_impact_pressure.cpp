// ImpactPressure: the modified-Newtonian impact law on cloth and its porous reduction, against the law's
// closed forms and by substituting the answer back into the two equations it must satisfy.

#include <gtest/gtest.h>

#include <cmath>

#include "structure/effects/ImpactPressure.hpp"

namespace fsi::structure {
namespace {

constexpr double kRho = 1.2;

TEST(ImpactPressure, ImpermeableClothFollowsTheImpactLaw) {
  const ClothPermeability tight;
  // Facing a 10 m/s wind: the stagnation pressure times C_p,max.
  EXPECT_DOUBLE_EQ(impactPressure({0, 0, 1}, {0, 0, 10}, kRho, 1.0, 2.0, tight).pressure, 0.5 * kRho * 100);
  EXPECT_DOUBLE_EQ(impactPressure({0, 0, 1}, {0, 0, 10}, kRho, 0.8, 2.0, tight).pressure,
                   0.8 * 0.5 * kRho * 100);
  // Inclined 60 deg: cos^2 = 1/4 (n = 2), cos = 1/2 (n = 1).
  const double s = std::sqrt(3.0) / 2;
  EXPECT_NEAR(impactPressure({s, 0, 0.5}, {0, 0, 10}, kRho, 1.0, 2.0, tight).pressure, 0.25 * 60, 1e-12);
  EXPECT_NEAR(impactPressure({s, 0, 0.5}, {0, 0, 10}, kRho, 1.0, 1.0, tight).pressure, 0.5 * 60, 1e-12);
  // Edge-on, from behind, no wind: nothing.
  EXPECT_EQ(impactPressure({1, 0, 0}, {0, 0, 10}, kRho, 1.0, 2.0, tight).pressure, 0.0);
  EXPECT_EQ(impactPressure({0, 0, -1}, {0, 0, 10}, kRho, 1.0, 2.0, tight).pressure, 0.0);
  EXPECT_EQ(impactPressure({0, 0, 1}, {0, 0, 0}, kRho, 1.0, 2.0, tight).pressure, 0.0);
}

TEST(ImpactPressure, PorousReductionSatisfiesTheClothLawAndTheReduction) {
  ClothPermeability cloth;
  cloth.a = 7e6;
  cloth.b = 200;
  for (double vn : {1.0, 5.0, 20.0, 60.0}) {
    const double dp0 = 0.5 * kRho * vn * vn;
    const ImpactLoad r = porousReduction(dp0, vn, kRho, cloth);
    ASSERT_GT(r.throughFlow, 0);
    ASSERT_LT(r.throughFlow, vn);
    // Darcy-Forchheimer at the through-flow, and the stagnation pressure reduced by the flow that passes.
    EXPECT_NEAR(r.pressure,
                cloth.a * cloth.viscosity * r.throughFlow + cloth.b * kRho * r.throughFlow * r.throughFlow,
                1e-10 * dp0)
        << vn;
    EXPECT_NEAR(r.pressure, dp0 * (1 - std::pow(r.throughFlow / vn, 2)), 1e-10 * dp0) << vn;
  }
}

TEST(ImpactPressure, PorousLimitsAndTrend) {
  const double vn = 8, dp0 = 0.5 * kRho * vn * vn;
  ClothPermeability open;
  open.a = 1e-6;
  const ImpactLoad none = porousReduction(dp0, vn, kRho, open);
  EXPECT_LT(none.pressure, 1e-6 * dp0) << "no resistance: the air passes, no load";
  EXPECT_NEAR(none.throughFlow, vn, 1e-6 * vn);
  ClothPermeability tight;
  tight.a = 1e13;
  const ImpactLoad full = porousReduction(dp0, vn, kRho, tight);
  EXPECT_NEAR(full.pressure, dp0, 1e-9 * dp0) << "a tight cloth carries the whole impact pressure";
  EXPECT_NEAR(full.throughFlow, dp0 / (tight.a * tight.viscosity), 1e-6 * full.throughFlow)
      << "Darcy's limit";
  // More porous (smaller a, b): less pressure, more through-flow.
  double last = dp0, lastU = 0;
  for (double a : {1e9, 1e8, 1e7, 1e6, 1e5}) {
    ClothPermeability c;
    c.a = a;
    c.b = a * 3e-5;
    const ImpactLoad r = porousReduction(dp0, vn, kRho, c);
    EXPECT_LT(r.pressure, last) << a;
    EXPECT_GT(r.throughFlow, lastU) << a;
    last = r.pressure;
    lastU = r.throughFlow;
  }
  // Impermeable cloth and degenerate inputs.
  EXPECT_EQ(porousReduction(dp0, vn, kRho, ClothPermeability{}).pressure, dp0);
  EXPECT_EQ(porousReduction(0, vn, kRho, tight).pressure, 0.0);
  EXPECT_EQ(porousReduction(dp0, 0, kRho, tight).pressure, dp0);
}

}  // namespace
}  // namespace fsi::structure

namespace fsi::structure {
namespace {

// A unit square of cloth in z = 0 (two triangles, normals +z), its nodes at rest or moving with velocity u.
struct Square {
  std::vector<double> x{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  std::vector<int> conn{0, 1, 2, 0, 2, 3};
  std::vector<double> v = std::vector<double>(12, 0.0);
  std::array<double, 3> force(const ImpactPressureLoad& load, double loadFactor = 1.0) const {
    std::vector<double> f(12, 0.0), fint(12, 0.0);
    ForceContext ctx;
    ctx.x = x.data();
    ctx.v = v.data();
    ctx.fext = f.data();
    ctx.fint = fint.data();
    ctx.loadFactor = loadFactor;
    load.addForces(ctx);
    std::array<double, 3> sum{};
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) sum[k] += f[3 * i + k];
    return sum;
  }
};

AirStream wind(double wx, double wy, double wz) {
  AirStream a;
  a.wind = {wx, wy, wz};
  a.density = kRho;
  return a;
}

TEST(ImpactPressure, TheLoadOnASquareIsPressureTimesArea) {
  const Square sq;
  const ImpactPressureLoad facing("sq", sq.conn, wind(0, 0, 10), 0.9, 2.0, ClothPermeability{});
  const auto f = sq.force(facing);
  EXPECT_NEAR(f[2], 0.9 * 0.5 * kRho * 100 * 1.0, 1e-12) << "p A along the normal";
  EXPECT_NEAR(f[0], 0.0, 1e-12);
  EXPECT_NEAR(sq.force(facing, 0.5)[2], 0.5 * f[2], 1e-12) << "scaled by the load factor";
  // The wind 60 deg off the normal: cos^2 = 1/4 of the stagnation pressure, still along the normal.
  const ImpactPressureLoad oblique("sq", sq.conn, wind(0, 10 * std::sqrt(3.0) / 2, 5), 1.0, 2.0,
                                   ClothPermeability{});
  EXPECT_NEAR(sq.force(oblique)[2], 0.25 * 0.5 * kRho * 100, 1e-12);
  EXPECT_NEAR(sq.force(oblique)[1], 0.0, 1e-12);
  // Cloth moving with the wind feels nothing; from behind, nothing.
  Square moving;
  for (int i = 0; i < 4; ++i) moving.v[3 * i + 2] = 10;
  EXPECT_NEAR(moving.force(facing)[2], 0.0, 1e-12);
  const ImpactPressureLoad behind("sq", sq.conn, wind(0, 0, -10), 1.0, 2.0, ClothPermeability{});
  EXPECT_EQ(sq.force(behind)[2], 0.0);
  // Porous cloth carries the reduced pressure.
  ClothPermeability cloth;
  cloth.a = 2e6;
  cloth.b = 50;
  const ImpactLoad r = porousReduction(0.5 * kRho * 100, 10, kRho, cloth);
  const ImpactPressureLoad porous("sq", sq.conn, wind(0, 0, 10), 1.0, 2.0, cloth);
  EXPECT_NEAR(sq.force(porous)[2], r.pressure, 1e-10);
  EXPECT_LT(r.pressure, 0.5 * kRho * 100);
  // The connectivity the assembler threads over: two triangles of three nodes.
  EXPECT_EQ(facing.connectivity().items, 2);
  EXPECT_EQ(facing.connectivity().nodesPerItem, 3);
}

}  // namespace
}  // namespace fsi::structure
