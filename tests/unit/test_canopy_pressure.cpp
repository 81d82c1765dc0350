// CanopyPressure: the inside pressure of a round canopy (Bernoulli to the mouth and continuity of the air
// inside) and the outside impact law and wake, against closed forms: a canopy holding its air sees the
// stagnation pressure, a vent or porous cloth lowers it by the leak's law, a growing canopy by the inflow it
// needs; a closed surface under the inside pressure alone carries no net force; a flat patch carries the
// difference of the inside and outside pressures.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "structure/effects/CanopyPressure.hpp"

namespace fsi::structure {
namespace {

constexpr double kRho = 1.2;
constexpr double kPi = 3.14159265358979323846;

CanopyState canopy(double speed, double mouth, double volumeRate = 0, double cloth = 0, double vent = 0) {
  CanopyState s;
  s.speed = speed;
  s.mouthArea = mouth;
  s.volumeRate = volumeRate;
  s.clothArea = cloth;
  s.ventArea = vent;
  return s;
}

TEST(CanopyPressure, AFullTightCanopySeesTheStagnationPressure) {
  const CanopyPressureParams prm;
  const double q = 0.5 * kRho * 20 * 20;
  EXPECT_NEAR(insidePressure(canopy(20, 0.5), kRho, prm), q, 1e-9 * q);
  EXPECT_EQ(insidePressure(canopy(0, 0.5), kRho, prm), 0.0) << "no wind, no pressure";
}

TEST(CanopyPressure, AVentLowersItByTheOrificeLaw) {
  // u_m = C_v A_v √(2p/ρ) / A_m and p = q − ½ρ u_m²: p = q / (1 + (C_v A_v / A_m)²).
  CanopyPressureParams prm;
  prm.ventDischarge = 0.6;
  const double q = 0.5 * kRho * 30 * 30, am = 0.8, av = 0.05;
  const double r = prm.ventDischarge * av / am;
  EXPECT_NEAR(insidePressure(canopy(30, am, 0, 0, av), kRho, prm), q / (1 + r * r), 1e-9 * q);
}

TEST(CanopyPressure, PorousClothLowersItByTheClothLaw) {
  // Darcy cloth (b = 0): u = p / (a μ), u_m = A_c u / A_m, p = q − ½ρ u_m²: k p² + p − q = 0 with
  // k = ½ρ (A_c / (a μ A_m))².
  CanopyPressureParams prm;
  const double q = 0.5 * kRho * 25 * 25, am = 1.0, ac = 3.0;
  double last = q;
  for (double a : {4e8, 1e8, 3e7}) {  // more porous cloth each time
    prm.cloth.a = a;
    const double k = 0.5 * kRho * std::pow(ac / (a * prm.cloth.viscosity * am), 2);
    const double expect = (-1 + std::sqrt(1 + 4 * k * q)) / (2 * k);
    const double p = insidePressure(canopy(25, am, 0, ac), kRho, prm);
    EXPECT_NEAR(p, expect, 1e-9 * q) << "a = " << a;
    EXPECT_LT(p, last) << "more porous, less pressure";
    last = p;
  }
  // The cloth's through-flow satisfies its law.
  prm.cloth.a = 7e6;
  prm.cloth.b = 200;
  const double u = clothThroughFlow(123.0, kRho, prm.cloth);
  EXPECT_NEAR(prm.cloth.a * prm.cloth.viscosity * u + prm.cloth.b * kRho * u * u, 123.0, 1e-10);
}

TEST(CanopyPressure, AGrowingCanopyDrawsItDownAShrinkingOneUp) {
  const CanopyPressureParams prm;  // suction_limit 1
  const double q = 0.5 * kRho * 20 * 20, am = 0.2;
  // No leak: u_m = V̇ / A_m, p = q − ½ρ u_m |u_m|.
  for (double vdot : {0.5, 2.0, -1.0}) {
    const double um = vdot / am;
    EXPECT_NEAR(insidePressure(canopy(20, am, vdot), kRho, prm), q - 0.5 * kRho * um * std::abs(um), 1e-9 * q)
        << "V' = " << vdot;
  }
  // Growing faster than air can come in: the floor −k q.
  EXPECT_NEAR(insidePressure(canopy(20, am, 10.0), kRho, prm), -q, 1e-12 * q);
  EXPECT_NEAR(insidePressure(canopy(20, 0.0, 1.0), kRho, prm), -q, 1e-12 * q) << "a closed mouth";
}

TEST(CanopyPressure, ProjectedRingAreaOfARegularPolygon) {
  // A regular 12-gon of circumradius 0.7 in a plane tilted to the axis' normal plane, its points shuffled:
  // area N/2 r² sin(2π/N).
  const int n = 12;
  const double r = 0.7;
  const std::array<double, 3> axis{0, std::sin(0.3), std::cos(0.3)};
  const std::array<double, 3> e1{1, 0, 0}, e2{0, std::cos(0.3), -std::sin(0.3)};
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  std::vector<double> pts;
  for (int i : order)
    for (int k = 0; k < 3; ++k)
      pts.push_back(1.0 + r * (std::cos(2 * kPi * i / n) * e1[k] + std::sin(2 * kPi * i / n) * e2[k]) +
                    0.3 * axis[k] * (i % 2));  // offsets along the axis do not count
  EXPECT_NEAR(projectedRingArea(pts, axis), 0.5 * n * r * r * std::sin(2 * kPi / n), 1e-12);
}

// A regular octahedron (vertices ±e_k), normals out: a closed surface.
struct Octahedron {
  std::vector<double> x{1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
  std::vector<int> conn{0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  std::vector<double> v = std::vector<double>(18, 0.0);
  std::vector<double> forces(const CanopyPressureLoad& load) const {
    std::vector<double> f(18, 0.0), fint(18, 0.0);
    ForceContext ctx;
    ctx.x = x.data();
    ctx.v = v.data();
    ctx.fext = f.data();
    ctx.fint = fint.data();
    load.addForces(ctx);
    return f;
  }
};

AirStream wind(double wx, double wy, double wz) {
  AirStream a;
  a.wind = {wx, wy, wz};
  a.density = kRho;
  return a;
}

TEST(CanopyPressure, InsidePressureOnAClosedShapeHasNoNetForce) {
  Octahedron o;
  CanopyPressureParams prm;
  prm.cpMax = 0;  // the inside alone
  const CanopyPressureLoad load("oct", o.conn, {0, 2, 1, 3}, {}, wind(0, 0, 15), prm);
  const auto f = o.forces(load);
  const double q = 0.5 * kRho * 15 * 15;
  double sum[3] = {0, 0, 0};
  for (int i = 0; i < 6; ++i)
    for (int k = 0; k < 3; ++k) sum[k] += f[3 * i + k];
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(sum[k], 0.0, 1e-12 * q);
  // Node 4 (+z) gets a third of q A n̂ from each of its 4 faces (A = √3/2, n̂ = (±1, ±1, 1)/√3): q (2/3) e_z.
  EXPECT_NEAR(f[3 * 4 + 2], q * 2.0 / 3.0, 1e-12 * q);
  // The volume rate of a homogeneous expansion v = ε x is 3 ε V (exact on flat triangles: v is linear).
  for (int i = 0; i < 18; ++i) o.v[i] = 0.1 * o.x[i];
  EXPECT_NEAR(load.state(o.x.data(), o.v.data(), 0.0).volumeRate, 0.3 * 4.0 / 3.0, 1e-12);
  EXPECT_NEAR(load.state(o.x.data(), o.v.data(), 0.0).mouthArea, 2.0, 1e-12) << "the equator's square";
}

TEST(CanopyPressure, AFlatPatchCarriesInsideLessOutside) {
  // A unit square, normal +z (out of the "canopy"), its corners the mouth (projected area 1, at rest):
  // inside q. Wind along −z meets the outer face: cp_max q presses in, net (1 − cp_max) q A. Wind along +z
  // leaves it leeward: the wake's suction adds, net (1 + wake_cp) q A.
  const std::vector<double> x{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const std::vector<int> conn{0, 1, 2, 0, 2, 3};
  auto fz = [&](const CanopyPressureLoad& load, double loadFactor = 1.0) {
    std::vector<double> f(12, 0.0), fint(12, 0.0), v(12, 0.0);
    ForceContext ctx;
    ctx.x = x.data();
    ctx.v = v.data();
    ctx.fext = f.data();
    ctx.fint = fint.data();
    ctx.loadFactor = loadFactor;
    load.addForces(ctx);
    return f[2] + f[5] + f[8] + f[11];
  };
  CanopyPressureParams prm;
  prm.cpMax = 0.8;
  prm.wakeCp = 0.4;
  const double q = 0.5 * kRho * 10 * 10;
  const CanopyPressureLoad facing("sq", conn, {0, 1, 2, 3}, {}, wind(0, 0, -10), prm);
  EXPECT_NEAR(fz(facing), 0.2 * q, 1e-12 * q);
  EXPECT_NEAR(fz(facing, 0.5), 0.1 * q, 1e-12 * q) << "scaled by the load factor";
  const CanopyPressureLoad leeward("sq", conn, {0, 1, 2, 3}, {}, wind(0, 0, 10), prm);
  EXPECT_NEAR(fz(leeward), 1.4 * q, 1e-12 * q);
  // The wind 60° off the outer normal: the impact law's cos² = 1/4.
  const CanopyPressureLoad oblique("sq", conn, {0, 1, 2, 3}, {}, wind(0, 10 * std::sqrt(3.0) / 2, -5), prm);
  EXPECT_NEAR(fz(oblique), q - 0.8 * 0.25 * q, 1e-9 * q)
      << "inside q (the mouth at rest holds its air whatever its area), outside cos² of it";
}

}  // namespace
}  // namespace fsi::structure
