// lanes::atan2 (structure/model/Lanes.hpp), the bending kernel's angle: against std::atan2 over every
// octant, near the octants' edges and the reduction's switch at tan(π/8), across magnitudes, and at the
// signed zeros and axes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "structure/model/Lanes.hpp"

using namespace fsi::structure;

namespace {

// |a − b| in units in the last place of b (the reference).
double ulps(double a, double b) {
  if (a == b) return 0;
  return std::abs(a - b) / (std::nextafter(std::abs(b), INFINITY) - std::abs(b));
}

double worstUlps(const std::vector<double>& ys, const std::vector<double>& xs) {
  double worst = 0;
  for (std::size_t i = 0; i + lanes::kWidth <= ys.size(); i += lanes::kWidth) {
    const lanes::Vd r = lanes::atan2(lanes::load(&ys[i]), lanes::load(&xs[i]));
    for (int l = 0; l < lanes::kWidth; ++l) {
      const double ref = std::atan2(ys[i + std::size_t(l)], xs[i + std::size_t(l)]);
      EXPECT_FALSE(std::isnan(r[l])) << ys[i + std::size_t(l)] << ", " << xs[i + std::size_t(l)];
      worst = std::max(worst, ulps(r[l], ref));
    }
  }
  return worst;
}

}  // namespace

TEST(LanesAtan2, WithinFourUlpsOfTheLibraryEverywhere) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), logScale(-12, 12);
  std::vector<double> ys, xs;
  for (int i = 0; i < 400000; ++i) {
    const double t = angle(rng), r = std::pow(10.0, logScale(rng));
    ys.push_back(r * std::sin(t));
    xs.push_back(r * std::cos(t));
  }
  // Ratios at the reduction's switch (tan π/8), at 1 (the octant edge) and tiny ones.
  for (double ratio :
       {0.41421356237309503, 0.41421356237309515, 0.4142135623730951, 1.0, 1.0 - 1e-16, 1e-9, 1e-300, 3.0})
    for (double sx : {1.0, -1.0})
      for (double sy : {1.0, -1.0}) {
        ys.push_back(sy * ratio);
        xs.push_back(sx);
        ys.push_back(sy);
        xs.push_back(sx * ratio);
      }
  while (ys.size() % lanes::kWidth != 0) ys.push_back(1.0), xs.push_back(1.0);
  EXPECT_LE(worstUlps(ys, xs), 4.0);
}

TEST(LanesAtan2, SmallAnglesKeepTheirRelativeAccuracy) {
  // The bending's Δθ near flat: atan2(y, 1) for tiny y must be y to round-off, not an absolute 1e-16.
  std::vector<double> ys, xs;
  for (int k = 0; k < 64; ++k) {
    const double y = std::ldexp(1.2345, -k);
    for (double s : {1.0, -1.0}) ys.push_back(s * y), xs.push_back(1.0);
  }
  EXPECT_LE(worstUlps(ys, xs), 2.0);
}

TEST(LanesAtan2, AxesAndSignedZerosAsTheLibrary) {
  const double z = 0.0;
  const std::vector<double> ys = {z, -z, z, -z, 1, -1, 1, -1, z, -z, 2, -2};
  const std::vector<double> xs = {z, z, -z, -z, z, z, -z, -z, 1, -1, 0, 0};
  for (std::size_t i = 0; i < ys.size(); i += lanes::kWidth) {
    const lanes::Vd r = lanes::atan2(lanes::load(&ys[i]), lanes::load(&xs[i]));
    for (int l = 0; l < lanes::kWidth; ++l) {
      const double ref = std::atan2(ys[i + std::size_t(l)], xs[i + std::size_t(l)]);
      EXPECT_EQ(r[l], ref) << ys[i + std::size_t(l)] << ", " << xs[i + std::size_t(l)];
      EXPECT_EQ(std::signbit(r[l]), std::signbit(ref));
    }
  }
}
