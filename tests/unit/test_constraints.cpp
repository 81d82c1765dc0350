// The sliding-plane projection both integrators use (PlaneSlider::project).
#include <gtest/gtest.h>

#include <cmath>

#include "structure/integrate/Constraints.hpp"

using namespace fsi::structure;

// An oblique plane: the normal part of the velocity goes, the tangential part stays, and the position loses
// the normal part of the step dt·v it just took, so a node that started on the plane stays on it.
TEST(PlaneSlider, ProjectionRemovesTheNormalVelocityAndStep) {
  PlaneSlider s;
  s.node = 0;
  const double c = 1.0 / std::sqrt(2.0);
  s.normal = {c, c, 0.0};  // the plane x + y = 0
  const double dt = 0.25;
  const double x0[3] = {1.0, -1.0, 0.5};  // on the plane
  double v[3] = {3.0, 1.0, -2.0};         // normal part (2, 2, 0), tangential (1, -1, -2)
  double x[3];
  for (int k = 0; k < 3; ++k) x[k] = x0[k] + dt * v[k];  // the step as the integrator took it
  const double vn = s.project(v, x, dt);
  EXPECT_NEAR(vn, 4.0 * c, 1e-14);
  EXPECT_NEAR(v[0], 1.0, 1e-14);
  EXPECT_NEAR(v[1], -1.0, 1e-14);
  EXPECT_NEAR(v[2], -2.0, 1e-14);
  EXPECT_NEAR(x[0] + x[1], 0.0, 1e-14);  // still on the plane
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(x[k], x0[k] + dt * v[k], 1e-14) << k;
}

// A velocity within the plane is left as it is (bit for bit: a zero normal part changes nothing).
TEST(PlaneSlider, TangentialMotionIsUnchanged) {
  PlaneSlider s;
  s.normal = {0.0, 0.0, 1.0};
  double v[3] = {0.3, -0.7, 0.0}, x[3] = {1.0, 2.0, 0.0};
  EXPECT_EQ(s.project(v, x, 1.0), 0.0);
  EXPECT_EQ(v[0], 0.3);
  EXPECT_EQ(v[1], -0.7);
  EXPECT_EQ(x[0], 1.0);
  EXPECT_EQ(x[1], 2.0);
  EXPECT_EQ(x[2], 0.0);
}
