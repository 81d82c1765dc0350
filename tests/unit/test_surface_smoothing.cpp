// SurfaceSmoothing (coupling/mapping/SurfaceSmoothing.hpp): constants kept, forces' sum kept by the transpose
// and the pair work-consistent, and a cosine on a grid damped by the heat equation's implicit step.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "coupling/mapping/SurfaceSmoothing.hpp"

using fsi::coupling::InterfaceMesh;
using fsi::coupling::SurfaceSmoothing;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A flat grid [0, L] × [0, b] of nx × ny quads; `split` cuts every other quad into two triangles (a mixed,
// irregular mesh).
InterfaceMesh grid(double L, double b, int nx, int ny, bool split) {
  InterfaceMesh m;
  m.name = "grid";
  for (int i = 0; i <= nx; ++i)
    for (int j = 0; j <= ny; ++j) m.points.push_back({L * i / nx, b * j / ny, 0.0});
  auto id = [&](int i, int j) { return i * (ny + 1) + j; };
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) {
      if (split && (i + j) % 2 == 1) {
        m.addFace({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        m.addFace({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        m.addFace({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  return m;
}

}  // namespace

TEST(SurfaceSmoothing, KeepsConstantsAndTheForcesSumAndIsWorkConsistent) {
  for (bool split : {false, true}) {
    InterfaceMesh m = grid(1.0, 0.3, 20, 6, split);
    // Warp it out of its plane a little: a curved surface.
    for (auto& p : m.points) p[2] = 0.1 * std::sin(3 * p[0]) * std::cos(5 * p[1]);
    const SurfaceSmoothing s(m, 0.05);
    const std::size_t n = m.points.size();
    std::vector<double> ones(3 * n, 1.0), out(3 * n);
    s.apply(ones.data(), out.data(), 3);
    for (double v : out) EXPECT_NEAR(v, 1.0, 1e-12);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<double> f(3 * n), d(3 * n), Sd(3 * n), Stf(3 * n);
    for (auto& v : f) v = u(rng);
    for (auto& v : d) v = u(rng);
    s.apply(d.data(), Sd.data(), 3);
    s.applyTranspose(f.data(), Stf.data(), 3);
    double fSd = 0, Stfd = 0, sum[3] = {0, 0, 0}, sumT[3] = {0, 0, 0};
    for (std::size_t k = 0; k < 3 * n; ++k) {
      fSd += f[k] * Sd[k];
      Stfd += Stf[k] * d[k];
      sum[k % 3] += f[k];
      sumT[k % 3] += Stf[k];
    }
    EXPECT_NEAR(fSd, Stfd, 1e-12 * std::abs(fSd) + 1e-12);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(sumT[c], sum[c], 1e-12);
    // A smoother averages: no value leaves the range of the input.
    double lo = 1e300, hi = -1e300;
    for (std::size_t k = 0; k < 3 * n; ++k) {
      lo = std::min(lo, Sd[k]);
      hi = std::max(hi, Sd[k]);
    }
    EXPECT_GE(lo, -1.0);
    EXPECT_LE(hi, 1.0);
  }
}

// On a grid of squares the cosines cos(kx) (k = mπ/L) are the discrete Laplacian's modes with the free
// boundary; the smoothing damps each by 1 / (1 + ℓ² (2 − 2 cos kh) / h²) exactly, which tends to the
// continuum's 1 / (1 + (kℓ)²) as h → 0.
TEST(SurfaceSmoothing, DampsACosineAsTheHeatEquationsImplicitStep) {
  const double L = 1.0, ell = 0.04;
  for (int m : {2, 8}) {
    const double k = m * kPi / L;
    double previous = 1e300;
    for (int nx : {40, 80, 160}) {
      const InterfaceMesh g = grid(L, 0.1, nx, 4, false);
      const SurfaceSmoothing s(g, ell);
      std::vector<double> d(g.points.size()), out(g.points.size());
      for (std::size_t i = 0; i < d.size(); ++i) d[i] = std::cos(k * g.points[i][0]);
      s.apply(d.data(), out.data(), 1);
      const double h = L / nx;
      const double discrete = 1 / (1 + ell * ell * (2 - 2 * std::cos(k * h)) / (h * h));
      const double continuum = 1 / (1 + k * k * ell * ell);
      for (std::size_t i = 0; i < d.size(); ++i) EXPECT_NEAR(out[i], discrete * d[i], 1e-10) << "m " << m;
      const double err = std::abs(discrete / continuum - 1);
      EXPECT_LT(err, previous);
      previous = err;
      if (nx == 160) {
        EXPECT_LT(err, 0.01) << "m " << m;
      }
    }
  }
}

TEST(SurfaceSmoothing, RefusesANonPositiveLengthAndAMeshWithoutFaces) {
  const InterfaceMesh g = grid(1, 1, 2, 2, false);
  EXPECT_THROW(SurfaceSmoothing(g, 0.0), std::invalid_argument);
  EXPECT_THROW(SurfaceSmoothing(g, -1.0), std::invalid_argument);
  InterfaceMesh empty;
  empty.points = {{0, 0, 0}};
  EXPECT_THROW(SurfaceSmoothing(empty, 0.1), std::invalid_argument);
}
