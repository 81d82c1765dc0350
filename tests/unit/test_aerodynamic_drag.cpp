// Line and body drag against the cross-flow formula: ½ ρ C_D d U² L on a line across the wind, the sin²θ law
// for an inclined line, nothing along the line or for a line moving with the air; ½ ρ C_D A |w| w on a body.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "structure/effects/AerodynamicDrag.hpp"

using namespace fsi::structure;

namespace {

struct Forces {
  std::vector<double> f;
  std::array<double, 3> total{0, 0, 0};
};

Forces apply(const Effect& e, const std::vector<double>& x, const std::vector<double>& v,
             double loadFactor = 1) {
  Forces r;
  r.f.assign(x.size(), 0.0);
  std::vector<double> fint(x.size(), 0.0);
  ForceContext ctx;
  ctx.x = x.data();
  ctx.v = v.data();
  ctx.fint = fint.data();
  ctx.fext = r.f.data();
  ctx.loadFactor = loadFactor;
  e.addForces(ctx);
  for (std::size_t i = 0; i < x.size(); ++i) r.total[i % 3] += r.f[i];
  return r;
}

AirStream wind(double ux, double uy, double uz) {
  AirStream a;
  a.wind = {ux, uy, uz};
  a.density = 1.2;
  a.function = TimeFunction::constant();
  return a;
}

}  // namespace

TEST(LineDrag, CrossFlowOnALineAcrossTheWind) {
  // A 2 m line along z in three elements, wind 10 m/s along x: F = ½ ρ C_D d U² L along x.
  const std::vector<double> x{0, 0, 0, 0, 0, 0.5, 0, 0, 1.2, 0, 0, 2.0};
  const std::vector<double> v(x.size(), 0.0);
  const LineDrag drag("l", {0, 1, 1, 2, 2, 3}, 2e-3, 1.1, wind(10, 0, 0));
  const Forces r = apply(drag, x, v);
  const double exact = 0.5 * 1.2 * 1.1 * 2e-3 * 100.0 * 2.0;
  EXPECT_NEAR(r.total[0], exact, exact * 1e-14);
  EXPECT_NEAR(r.total[1], 0.0, 1e-15);
  EXPECT_NEAR(r.total[2], 0.0, 1e-15);
  // The end node of the 0.8 m element carries half of it.
  EXPECT_NEAR(r.f[9], 0.5 * exact * 0.8 / 2.0, exact * 1e-14);
  // Incremental loading scales the force linearly.
  EXPECT_NEAR(apply(drag, x, v, 0.25).total[0], 0.25 * exact, exact * 1e-14);
}

TEST(LineDrag, InclinedLineFollowsTheSineSquaredLaw) {
  const double U = 8.0, L = 1.5, theta = 0.4;  // line at θ to the wind, in the x-z plane
  const std::vector<double> x{0, 0, 0, L * std::cos(theta), 0, L * std::sin(theta)};
  const std::vector<double> v(6, 0.0);
  const Forces r = apply(LineDrag("l", {0, 1}, 1e-3, 1.0, wind(U, 0, 0)), x, v);
  const double mag = 0.5 * 1.2 * 1e-3 * std::pow(U * std::sin(theta), 2) * L;
  // Normal to the line, in the plane of line and wind: direction (sin²θ, 0, −sinθ cosθ)/sinθ.
  EXPECT_NEAR(r.total[0], mag * std::sin(theta), mag * 1e-13);
  EXPECT_NEAR(r.total[2], -mag * std::cos(theta), mag * 1e-13);
  // Along the wind: no drag; moving with the wind: no drag.
  const std::vector<double> along{0, 0, 0, 1, 0, 0};
  EXPECT_NEAR(apply(LineDrag("l", {0, 1}, 1e-3, 1.0, wind(U, 0, 0)), along, v).total[0], 0.0, 1e-15);
  const std::vector<double> moving{U, 0, 0, U, 0, 0};
  EXPECT_NEAR(apply(LineDrag("l", {0, 1}, 1e-3, 1.0, wind(U, 0, 0)), x, moving).total[0], 0.0, 1e-15);
}

TEST(BodyDrag, QuadraticInTheRelativeWind) {
  const std::vector<double> x{0, 0, 0};
  const std::vector<double> v{1, 0, -2};  // relative wind (9, 0, 2)
  const Forces r = apply(BodyDrag("payload", {0}, 0.5, wind(10, 0, 0)), x, v);
  const double w = std::sqrt(81.0 + 4.0);
  EXPECT_NEAR(r.total[0], 0.5 * 1.2 * 0.5 * w * 9.0, 1e-12);
  EXPECT_NEAR(r.total[2], 0.5 * 1.2 * 0.5 * w * 2.0, 1e-12);
}
