// MomentConservation (coupling/mapping/MomentConservation.hpp): the corrected loads carry the target moment
// with their sum unchanged (the two conservation laws, to round-off), the correction is the smallest such
// traction, the moment the plain transfer Hᵀ loses between non-matching curved surfaces is restored, nothing
// changes where the surfaces coincide, and a cable's own axis is left and reported.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "coupling/mapping/L2Projection.hpp"
#include "coupling/mapping/MomentConservation.hpp"

namespace fsi::coupling {
namespace {

using Vec3 = std::array<double, 3>;

// A quarter of a cylinder of radius R and length L, nθ × nz quads cut into triangles, the angles shifted by
// `shift` cells (0.5: no node of one resolution on a node of another), its axis raised by `height` along z
// (moments about the origin are then taken about a point below it, as a canopy's about its anchor). Coarse
// facets lie inside the curved surface by up to R(1 − cos(Δθ/2)): the gap of two non-matching resolutions.
InterfaceMesh cylinderPatch(int nt, int nz, double R, double L, double shift, double height = 0) {
  InterfaceMesh m;
  m.name = "cylinder";
  const double span = std::acos(-1.0) / 2;
  for (int i = 0; i <= nt; ++i)
    for (int j = 0; j <= nz; ++j) {
      const double t = span * std::clamp((i + (i > 0 && i < nt ? shift : 0.0)) / nt, 0.0, 1.0);
      m.points.push_back({R * std::cos(t), L * j / nz, height + R * std::sin(t)});
    }
  auto id = [&](int i, int j) { return i * (nz + 1) + j; };
  for (int i = 0; i < nt; ++i)
    for (int j = 0; j < nz; ++j) {
      m.addFace({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.addFace({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

std::vector<double> positions(const InterfaceMesh& m) {
  std::vector<double> x;
  for (const Vec3& p : m.points) x.insert(x.end(), p.begin(), p.end());
  return x;
}

void totals(const std::vector<double>& x, const std::vector<double>& f, Eigen::Vector3d& force,
            Eigen::Vector3d& moment) {
  force.setZero();
  moment.setZero();
  for (std::size_t i = 0; 3 * i < f.size(); ++i) {
    const Eigen::Vector3d fi(f[3 * i], f[3 * i + 1], f[3 * i + 2]);
    force += fi;
    moment += Eigen::Vector3d(x[3 * i], x[3 * i + 1], x[3 * i + 2]).cross(fi);
  }
}

// A load like a pressure with shear: normal pressure varying along the surface plus a tangential part,
// times the points' lumped areas (target-side nodal forces); `height` as the patch's.
std::vector<double> surfaceLoad(const InterfaceMesh& m, double height = 0) {
  const std::vector<double> area = m.pointAreas();
  std::vector<double> f;
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const Vec3 p{m.points[i][0], m.points[i][1], m.points[i][2] - height};
    const double r = std::hypot(p[0], p[2]);
    const double pressure = 1000 * (1 + 0.6 * std::sin(3 * p[1]) + 0.4 * p[0]);
    const double shear = 50 * std::cos(2 * p[1]);
    f.push_back(area[i] * (-pressure * p[0] / r - shear * p[2] / r));
    f.push_back(area[i] * 20 * p[2]);
    f.push_back(area[i] * (-pressure * p[2] / r + shear * p[0] / r));
  }
  return f;
}

}  // namespace

TEST(MomentConservation, CarriesTheTargetMomentAndKeepsTheForce) {
  const InterfaceMesh m = cylinderPatch(12, 8, 1.5, 2.0, 0.0);
  const std::vector<double> x = positions(m);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> f(x.size());
  for (auto& v : f) v = u(rng);
  Eigen::Vector3d force0, moment0, force1, moment1;
  totals(x, f, force0, moment0);
  const Vec3 target{moment0[0] + 3.0, moment0[1] - 2.0, moment0[2] + 0.5};
  const MomentConservation mc = MomentConservation::onSurface(m);
  const MomentCorrection r = mc.apply(x.data(), f.data(), target);
  totals(x, f, force1, moment1);
  EXPECT_NEAR(r.defect[0], 3.0, 1e-12);
  EXPECT_NEAR(r.defect[1], -2.0, 1e-12);
  EXPECT_NEAR(r.defect[2], 0.5, 1e-12);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(force1[k], force0[k], 1e-12) << k;
    EXPECT_NEAR(moment1[k], target[std::size_t(k)], 1e-12) << k;
    EXPECT_EQ(r.remaining[std::size_t(k)], 0.0);
  }
  EXPECT_GT(r.largestNodalForce, 0.0);
}

// The correction δ is the smallest in Σ |δ_i|² / w_i (the L2 norm of the traction δ_i / w_i) among all with
// the same resultant and moment: adding any ε with Σ ε = 0 and Σ x × ε = 0 makes it larger.
TEST(MomentConservation, IsTheSmallestTractionWithThatMoment) {
  const InterfaceMesh m = cylinderPatch(10, 6, 1.0, 1.0, 0.3);
  const std::vector<double> x = positions(m);
  const std::vector<double> w = m.pointAreas();
  const std::size_t n = w.size();
  std::vector<double> delta(3 * n, 0.0);
  MomentConservation(w).apply(x.data(), delta.data(), {0.4, -1.0, 2.0});
  auto norm = [&](const std::vector<double>& d) {
    double s = 0;
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) s += d[3 * i + std::size_t(k)] * d[3 * i + std::size_t(k)] / w[i];
    return s;
  };
  // The six constraints as rows of C (force, moment); ε = (I − W Cᵀ (C W Cᵀ)⁻¹ C) e keeps both at zero.
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(6, Eigen::Index(3 * n));
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Index c = Eigen::Index(3 * i);
    C.block<3, 3>(0, c).setIdentity();
    const Eigen::Vector3d p(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
    C.block<3, 3>(3, c) << 0, -p[2], p[1], p[2], 0, -p[0], -p[1], p[0], 0;  // p × ε
  }
  Eigen::VectorXd W(3 * n);
  for (std::size_t i = 0; i < 3 * n; ++i) W[Eigen::Index(i)] = w[i / 3];
  const Eigen::MatrixXd CW = C * W.asDiagonal();
  const Eigen::MatrixXd G = (CW * C.transpose()).inverse();
  std::mt19937 rng(4);
  std::normal_distribution<double> g;
  const double best = norm(delta);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd e(3 * n);
    for (auto& v : e) v = g(rng);
    const Eigen::VectorXd eps = 1e-3 * (e - CW.transpose() * (G * (C * e)));
    ASSERT_LT((C * eps).norm(), 1e-12);
    std::vector<double> d = delta;
    for (std::size_t k = 0; k < 3 * n; ++k) d[k] += eps[Eigen::Index(k)];
    EXPECT_GT(norm(d), best);
  }
}

// The physical case: a fine curved fluid skin and a coarse structure's facets inside it. The plain transfer
// Hᵀ keeps the force but loses moment to the gap; the correction restores it to round-off, with nodal
// forces small against the loads.
TEST(MomentConservation, RestoresTheMomentHTransposeLosesOnCurvedNonMatchingSurfaces) {
  const InterfaceMesh structure = cylinderPatch(8, 5, 1.5, 2.0, 0.0, 3.0);
  const InterfaceMesh fluid = cylinderPatch(40, 24, 1.5, 2.0, 0.5, 3.0);
  ProjectionOptions o;
  o.gapCorrection = false;  // as the adapter's default: the gap is then not carried across
  o.defectCorrection = ProjectionOptions::Defect::Off;
  const L2Projection h(structure, fluid, o);
  ASSERT_TRUE(h.report().allMapped());
  const std::vector<double> ff = surfaceLoad(fluid, 3.0), xf = positions(fluid), xs = positions(structure);
  std::vector<double> fs(xs.size());
  h.applyTranspose(ff.data(), fs.data(), 3);
  Eigen::Vector3d forceF, momentF, forceS, momentS;
  totals(xf, ff, forceF, momentF);
  totals(xs, fs, forceS, momentS);
  const double scale = momentF.cwiseAbs().maxCoeff();
  ASSERT_LT((forceS - forceF).cwiseAbs().maxCoeff(), 1e-12 * forceF.cwiseAbs().maxCoeff());
  const double before = (momentS - momentF).cwiseAbs().maxCoeff() / scale;
  EXPECT_GT(before, 1e-5);  // the gap's moment (2.4e-5 of it here), without which this would prove nothing
  double largestLoad = 0;
  for (std::size_t i = 0; 3 * i < fs.size(); ++i)
    largestLoad = std::max(largestLoad, std::hypot(fs[3 * i], fs[3 * i + 1], fs[3 * i + 2]));
  const MomentCorrection r = MomentConservation::onSurface(structure).apply(
      xs.data(), fs.data(), {momentF[0], momentF[1], momentF[2]});
  Eigen::Vector3d forceC, momentC;
  totals(xs, fs, forceC, momentC);
  const double after = (momentC - momentF).cwiseAbs().maxCoeff() / scale;
  std::printf(
      "  moment fluid vs structure: %.2e plain, %.2e corrected; largest nodal correction %.2e of the "
      "largest load\n",
      before, after, r.largestNodalForce / largestLoad);
  EXPECT_LT(after, 1e-12);
  EXPECT_LT((forceC - forceF).cwiseAbs().maxCoeff(), 1e-12 * forceF.cwiseAbs().maxCoeff());
  EXPECT_LT(r.largestNodalForce, 0.05 * largestLoad);
}

// Coincident surfaces (the same mesh on both sides): H reproduces positions, the moment is already
// carried, the correction is round-off.
TEST(MomentConservation, ChangesNothingWhereTheSurfacesCoincide) {
  const InterfaceMesh m = cylinderPatch(10, 6, 1.5, 2.0, 0.0);
  ProjectionOptions o;
  o.gapCorrection = false;
  const L2Projection h(m, m, o);
  const std::vector<double> ff = surfaceLoad(m), x = positions(m);
  std::vector<double> fs(x.size());
  h.applyTranspose(ff.data(), fs.data(), 3);
  Eigen::Vector3d forceF, momentF;
  totals(x, ff, forceF, momentF);
  const std::vector<double> plain = fs;
  const MomentCorrection r =
      MomentConservation::onSurface(m).apply(x.data(), fs.data(), {momentF[0], momentF[1], momentF[2]});
  double largest = 0, change = 0;
  for (std::size_t k = 0; k < fs.size(); ++k) {
    largest = std::max(largest, std::abs(plain[k]));
    change = std::max(change, std::abs(fs[k] - plain[k]));
  }
  EXPECT_LT(change, 1e-12 * largest);
  EXPECT_LT(r.largestNodalForce, 1e-12 * largest);
}

// Points on one line (a cable): the moment about the line's own axis cannot be carried by a × r; it is
// left and reported, the rest is corrected, nothing is NaN.
TEST(MomentConservation, LeavesACableAxisMomentAndReportsIt) {
  std::vector<double> x, f;
  for (int i = 0; i <= 10; ++i) {
    x.insert(x.end(), {0.1 * i, 0.1 * i, 0.0});
    f.insert(f.end(), {0.0, 0.0, -1.0});
  }
  InterfaceMesh cable;
  for (std::size_t i = 0; 3 * i < x.size(); ++i)
    cable.points.push_back({x[3 * i], x[3 * i + 1], x[3 * i + 2]});
  Eigen::Vector3d force0, moment0, force1, moment1;
  totals(x, f, force0, moment0);
  const Eigen::Vector3d axis = Eigen::Vector3d(1, 1, 0).normalized(), across(0, 0, 1);
  const Eigen::Vector3d target = moment0 + 2.0 * axis + 3.0 * across;
  const MomentCorrection r =
      MomentConservation::onSurface(cable).apply(x.data(), f.data(), {target[0], target[1], target[2]});
  totals(x, f, force1, moment1);
  const Eigen::Vector3d remaining(r.remaining[0], r.remaining[1], r.remaining[2]);
  EXPECT_LT((remaining - 2.0 * axis).norm(), 1e-9);
  EXPECT_LT((moment1 - (target - remaining)).norm(), 1e-9);
  EXPECT_LT((force1 - force0).norm(), 1e-12);
  for (double v : f) EXPECT_TRUE(std::isfinite(v));
}

TEST(MomentConservation, RefusesBadWeights) {
  EXPECT_THROW(MomentConservation(std::vector<double>{1.0, -1.0}), std::invalid_argument);
  EXPECT_THROW(MomentConservation(std::vector<double>{1.0, std::nan("")}), std::invalid_argument);
  EXPECT_THROW(MomentConservation(std::vector<double>{0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(MomentConservation(std::vector<double>{}), std::invalid_argument);
}

}  // namespace fsi::coupling
