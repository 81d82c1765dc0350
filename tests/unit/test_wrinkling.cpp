// Wrinkling law: every branch against hand-derived plane-stress / tension-field values.
#include <gtest/gtest.h>

#include <cmath>

#include "structure/material/WrinklingMembrane.hpp"

using namespace fsi::structure;

namespace {
constexpr double Y = 1000.0, nu = 0.3;
const double c11 = Y / (1 - nu * nu);
}  // namespace

TEST(Wrinkling, SlackWhenBothPrincipalStrainsAreCompressive) {
  double S[3], w;
  EXPECT_EQ(wrinklingStress(-0.01, -0.02, 0.001, Y, c11, nu, S, w), WrinkleState::Slack);
  EXPECT_EQ(S[0], 0.0);
  EXPECT_EQ(S[1], 0.0);
  EXPECT_EQ(S[2], 0.0);
  EXPECT_EQ(w, 0.0);
  // Zero strain is slack too (no stress either way).
  EXPECT_EQ(wrinklingStress(0, 0, 0, Y, c11, nu, S, w), WrinkleState::Slack);
}

TEST(Wrinkling, TautGivesPlaneStressHooke) {
  double S[3], w;
  EXPECT_EQ(wrinklingStress(0.01, 0.004, 0.002, Y, c11, nu, S, w), WrinkleState::Taut);
  EXPECT_DOUBLE_EQ(S[0], c11 * (0.01 + nu * 0.004));
  EXPECT_DOUBLE_EQ(S[1], c11 * (0.004 + nu * 0.01));
  EXPECT_DOUBLE_EQ(S[2], c11 * (1 - nu) / 2 * 0.002);
  // Just inside the taut side of the boundary e2 = -nu e1: uniaxial stress, S2 = 0.
  EXPECT_EQ(wrinklingStress(0.01, -nu * 0.01 + 1e-13, 0.0, Y, c11, nu, S, w), WrinkleState::Taut);
  EXPECT_NEAR(S[0], Y * 0.01, 1e-9);  // round-off of c11 (e1 + nu e2) with e2 + nu e1 = 1e-13
  EXPECT_NEAR(S[1], 0.0, 1e-9);
}

TEST(Wrinkling, WrinkledGivesUniaxialStressAlongMajorStrain) {
  double S[3], w;
  // Principal strains 0.01 and -0.01 at 30 degrees: e = R diag(0.01, -0.01) Rᵀ.
  const double th = M_PI / 6, c = std::cos(th), s = std::sin(th);
  const double e11 = 0.01 * c * c - 0.01 * s * s, e22 = 0.01 * s * s - 0.01 * c * c, e12 = 0.02 * c * s;
  ASSERT_EQ(wrinklingStress(e11, e22, 2 * e12, Y, c11, nu, S, w), WrinkleState::Wrinkled);
  const double s1 = Y * 0.01;  // uniaxial: σ1 = Y ε1, σ2 = 0
  EXPECT_NEAR(S[0], s1 * c * c, 1e-12);
  EXPECT_NEAR(S[1], s1 * s * s, 1e-12);
  EXPECT_NEAR(S[2], s1 * c * s, 1e-12);
  EXPECT_NEAR(w, 0.5 * s1 * 0.01, 1e-15);
  // Minor principal stress is zero: det S = 0.
  EXPECT_NEAR(S[0] * S[1] - S[2] * S[2], 0.0, 1e-12 * s1 * s1);
}

TEST(Wrinkling, EnergyIsContinuousAndStressIsItsGradient) {
  // Walk across the taut / wrinkled boundary (e2 = -nu e1) and the wrinkled / slack one (e1 = 0).
  for (double e22 : {-0.0031, -0.0029, -0.001, 0.002}) {
    for (double g : {0.0, 0.004}) {
      double S[3], w;
      const double e11 = 0.01;
      wrinklingStress(e11, e22, g, Y, c11, nu, S, w);
      const double h = 1e-8;
      double Sp[3], Sm[3], wp, wm;
      wrinklingStress(e11 + h, e22, g, Y, c11, nu, Sp, wp);
      wrinklingStress(e11 - h, e22, g, Y, c11, nu, Sm, wm);
      EXPECT_NEAR((wp - wm) / (2 * h), S[0], 1e-5 * Y * 0.01) << e22;
      wrinklingStress(e11, e22 + h, g, Y, c11, nu, Sp, wp);
      wrinklingStress(e11, e22 - h, g, Y, c11, nu, Sm, wm);
      EXPECT_NEAR((wp - wm) / (2 * h), S[1], 1e-5 * Y * 0.01) << e22;
      wrinklingStress(e11, e22, g + h, Y, c11, nu, Sp, wp);
      wrinklingStress(e11, e22, g - h, Y, c11, nu, Sm, wm);
      EXPECT_NEAR((wp - wm) / (2 * h), S[2], 1e-5 * Y * 0.01) << e22;  // S12 = dW/d(2E12)
    }
  }
  // Energy continuous at the taut/wrinkled boundary.
  double S[3], wa, wb;
  wrinklingStress(0.01, -nu * 0.01 + 1e-12, 0, Y, c11, nu, S, wa);
  wrinklingStress(0.01, -nu * 0.01 - 1e-12, 0, Y, c11, nu, S, wb);
  EXPECT_NEAR(wa, wb, 1e-12);
}
