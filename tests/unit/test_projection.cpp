// Non-matching interface projection: closest-point search (against brute force), the consistent and lumped
// L2 projections (linear reproduction, second-order convergence, conservation of force and moment by the
// transpose, mesh-size ratios, curved surfaces with gaps) and the interface readers (OpenFOAM, Gmsh).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "coupling/interface/InterfaceIO.hpp"
#include "coupling/interface/SurfaceSearch.hpp"
#include "coupling/mapping/L2Projection.hpp"
#include "coupling/mapping/MapCheck.hpp"
#include "coupling/scheme/CouplingOptions.hpp"
#include "structure/model/Error.hpp"

namespace fsi::coupling {
namespace {

namespace fs = std::filesystem;
using Vec3 = std::array<double, 3>;
using Surface = std::function<Vec3(double, double)>;
using Field = std::function<double(const Vec3&)>;

const Surface kFlat = [](double u, double v) { return Vec3{u, 0.8 * v, 0.0}; };
// A 70° arc of the unit cylinder, 1 high.
const Surface kCylinder = [](double u, double v) {
  const double t = -0.6 + 1.2 * u;
  return Vec3{std::cos(t), std::sin(t), v};
};
// A patch of the unit sphere, 1 rad in longitude and 0.8 rad in latitude.
const Surface kSphere = [](double u, double v) {
  const double lon = -0.5 + u, lat = -0.4 + 0.8 * v;
  return Vec3{std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat)};
};

// (nx+1)(ny+1) grid points of the parameter square mapped by `s`; interior points moved at random by up to
// `perturb` cells in parameter space, so the mesh stays on the surface.
std::vector<Vec3> gridPoints(int nx, int ny, const Surface& s, double perturb, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-perturb, perturb);
  std::vector<Vec3> p;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      double u = double(i) / nx, v = double(j) / ny;
      if (perturb > 0 && i > 0 && i < nx && j > 0 && j < ny) {
        u += d(rng) / nx;
        v += d(rng) / ny;
      }
      p.push_back(s(u, v));
    }
  return p;
}

InterfaceMesh triangleGrid(int nx, int ny, const Surface& s, double perturb = 0.0, unsigned seed = 1) {
  InterfaceMesh m;
  m.name = "triangles";
  m.points = gridPoints(nx, ny, s, perturb, seed);
  auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        m.addFace({a, b, c});
        m.addFace({a, c, d});
      } else {
        m.addFace({a, b, d});
        m.addFace({b, c, d});
      }
    }
  return m;
}

InterfaceMesh quadGrid(int nx, int ny, const Surface& s, double perturb = 0.0, unsigned seed = 2) {
  InterfaceMesh m;
  m.name = "quads";
  m.points = gridPoints(nx, ny, s, perturb, seed);
  auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) m.addFace({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  return m;
}

std::vector<double> sample(const InterfaceMesh& m, const Field& f) {
  std::vector<double> v;
  for (const Vec3& p : m.points) v.push_back(f(p));
  return v;
}

std::vector<double> project(const L2Projection& h, const std::vector<double>& us) {
  std::vector<double> ut(std::size_t(h.targetSize()));
  h.apply(us.data(), ut.data());
  return ut;
}

// Max nodal error relative to the field's range at the target nodes.
double maxRelativeError(const InterfaceMesh& m, const std::vector<double>& u, const Field& f) {
  double lo = HUGE_VAL, hi = -HUGE_VAL, err = 0.0;
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const double e = f(m.points[i]);
    lo = std::min(lo, e);
    hi = std::max(hi, e);
    err = std::max(err, std::abs(u[i] - e));
  }
  return err / (hi - lo);
}

// ||u_h - f||_L2 over the target surface, by the 6-point degree-4 rule on every fan triangle.
double l2Error(const InterfaceMesh& m, const std::vector<double>& u, const Field& f) {
  const FanTriangulation fan(m);
  const double a = 0.445948490915965, b = 0.091576213509771;
  const double wa = 0.223381589678011, wb = 0.109951743655322;
  const std::array<std::pair<Vec3, double>, 6> rule{{{{a, a, 1 - 2 * a}, wa},
                                                     {{a, 1 - 2 * a, a}, wa},
                                                     {{1 - 2 * a, a, a}, wa},
                                                     {{b, b, 1 - 2 * b}, wb},
                                                     {{b, 1 - 2 * b, b}, wb},
                                                     {{1 - 2 * b, b, b}, wb}}};
  double sum = 0.0;
  for (int t = 0; t < fan.numTriangles(); ++t) {
    const double area = fan.area(t);
    for (const auto& [bary, w] : rule) {
      const double e = fan.interpolate(t, bary, u.data()) - f(fan.position(t, bary));
      sum += w * area * e * e;
    }
  }
  return std::sqrt(sum);
}

// Random nodal forces (mean not zero) and the relative errors of their total force and total moment about
// `origin` after F_s = Hᵀ F_t, relative to Σ|F| and Σ|r||F|.
std::pair<double, double> conservationErrors(const L2Projection& h, const InterfaceMesh& src,
                                             const InterfaceMesh& dst, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  std::vector<double> ft(std::size_t(3 * dst.numPoints())), fs(std::size_t(3 * src.numPoints()));
  for (std::size_t i = 0; i < ft.size(); ++i) ft[i] = d(rng) + (i % 3 == 2 ? 0.5 : 0.0);
  h.applyTranspose(ft.data(), fs.data(), 3);
  Vec3 origin{0, 0, 0};
  for (const Vec3& p : dst.points)
    for (int k = 0; k < 3; ++k) origin[k] += p[k] / dst.numPoints();
  auto sums = [&](const InterfaceMesh& m, const std::vector<double>& f, Vec3& force, Vec3& moment,
                  double& scaleF, double& scaleM) {
    force = moment = {0, 0, 0};
    scaleF = scaleM = 0;
    for (int i = 0; i < m.numPoints(); ++i) {
      const Vec3 r{m.points[i][0] - origin[0], m.points[i][1] - origin[1], m.points[i][2] - origin[2]};
      const double* fi = &f[3 * std::size_t(i)];
      for (int k = 0; k < 3; ++k) force[k] += fi[k];
      moment[0] += r[1] * fi[2] - r[2] * fi[1];
      moment[1] += r[2] * fi[0] - r[0] * fi[2];
      moment[2] += r[0] * fi[1] - r[1] * fi[0];
      const double fn = std::sqrt(fi[0] * fi[0] + fi[1] * fi[1] + fi[2] * fi[2]);
      scaleF += fn;
      scaleM += fn * std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    }
  };
  Vec3 ft1, mt1, fs1, ms1;
  double sf, sm, unused1, unused2;
  sums(dst, ft, ft1, mt1, sf, sm);
  sums(src, fs, fs1, ms1, unused1, unused2);
  double ef = 0, em = 0;
  for (int k = 0; k < 3; ++k) {
    ef = std::max(ef, std::abs(fs1[k] - ft1[k]));
    em = std::max(em, std::abs(ms1[k] - mt1[k]));
  }
  return {ef / sf, em / sm};
}

// ---------------------------------------------------------------------------------------------------------
// Search

// Independent reference: projection onto the plane when inside, else the closest of the three edges.
double bruteDistance(const FanTriangulation& fan, const Vec3& x, Vec3& closest) {
  double best = HUGE_VAL;
  auto consider = [&](const Vec3& q) {
    const double d = std::hypot(x[0] - q[0], x[1] - q[1], x[2] - q[2]);
    if (d < best) {
      best = d;
      closest = q;
    }
  };
  for (int t = 0; t < fan.numTriangles(); ++t) {
    const Vec3 a = fan.position(t, {1, 0, 0}), b = fan.position(t, {0, 1, 0}), c = fan.position(t, {0, 0, 1});
    const Vec3 e1{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const Vec3 r{x[0] - a[0], x[1] - a[1], x[2] - a[2]};
    const double g11 = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2];
    const double g12 = e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2];
    const double g22 = e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2];
    const double r1 = r[0] * e1[0] + r[1] * e1[1] + r[2] * e1[2],
                 r2 = r[0] * e2[0] + r[1] * e2[1] + r[2] * e2[2];
    const double det = g11 * g22 - g12 * g12;
    const double s = (g22 * r1 - g12 * r2) / det, t2 = (g11 * r2 - g12 * r1) / det;
    if (s >= 0 && t2 >= 0 && s + t2 <= 1)
      consider({a[0] + s * e1[0] + t2 * e2[0], a[1] + s * e1[1] + t2 * e2[1], a[2] + s * e1[2] + t2 * e2[2]});
    const std::array<std::pair<Vec3, Vec3>, 3> edges{{{a, b}, {b, c}, {c, a}}};
    for (const auto& [p, q] : edges) {
      const Vec3 pq{q[0] - p[0], q[1] - p[1], q[2] - p[2]};
      const double len2 = pq[0] * pq[0] + pq[1] * pq[1] + pq[2] * pq[2];
      const double u = std::clamp(
          ((x[0] - p[0]) * pq[0] + (x[1] - p[1]) * pq[1] + (x[2] - p[2]) * pq[2]) / len2, 0.0, 1.0);
      consider({p[0] + u * pq[0], p[1] + u * pq[1], p[2] + u * pq[2]});
    }
  }
  return best;
}

TEST(SurfaceSearch, MatchesBruteForceOnWavyMixedSurface) {
  // Wavy, perturbed quads; every third one split into two triangles.
  const Surface wavy = [](double u, double v) {
    return Vec3{u, v, 0.25 * std::sin(5 * u) * std::cos(4 * v) + 0.1 * u * v};
  };
  const InterfaceMesh q = quadGrid(17, 13, wavy, 0.3, 11);
  InterfaceMesh m;
  m.points = q.points;
  for (int f = 0; f < q.numFaces(); ++f) {
    const int* v = q.face(f);
    if (f % 3 == 0) {
      m.addFace({v[0], v[1], v[2]});
      m.addFace({v[0], v[2], v[3]});
    } else {
      m.addFace({v[0], v[1], v[2], v[3]});
    }
  }
  const SurfaceSearch search(m);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> d(-0.4, 1.4);
  std::uniform_int_distribution<int> anyTriangle(0, search.fan().numTriangles() - 1);
  for (int n = 0; n < 2000; ++n) {
    const Vec3 x{d(rng), d(rng), 0.8 * d(rng) - 0.4};
    const SurfacePoint p = search.closest(x, n % 2 ? anyTriangle(rng) : -1);
    Vec3 ref;
    const double dist = bruteDistance(search.fan(), x, ref);
    ASSERT_NEAR(p.distance, dist, 1e-12) << "query " << n;
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(p.point[k], ref[k], 1e-9) << "query " << n;
    ASSERT_EQ(p.face, search.fan().triangleFace[p.triangle]);
    ASSERT_TRUE(p.mapped);
    for (double b : p.bary) ASSERT_GE(b, -1e-12);
  }
}

TEST(SurfaceSearch, ToleranceDecidesMapped) {
  const SurfaceSearch search(quadGrid(4, 4, [](double u, double v) { return Vec3{u, v, 0}; }), 0.2);
  const SurfacePoint above = search.closest({0.3, 0.6, 0.1});
  EXPECT_TRUE(above.mapped);
  EXPECT_NEAR(above.distance, 0.1, 1e-14);
  EXPECT_NEAR(above.point[0], 0.3, 1e-14);
  EXPECT_NEAR(above.point[1], 0.6, 1e-14);
  const SurfacePoint far = search.closest({0.3, 0.6, 0.5});
  EXPECT_FALSE(far.mapped);
  EXPECT_NEAR(far.distance, 0.5, 1e-14);  // still the true closest point, flagged
  const SurfacePoint beside = search.closest({1.5, 0.25, 0.0});
  EXPECT_FALSE(beside.mapped);
  EXPECT_NEAR(beside.distance, 0.5, 1e-14);
  EXPECT_NEAR(beside.point[0], 1.0, 1e-14);
  EXPECT_NEAR(beside.point[1], 0.25, 1e-14);
}

TEST(SurfaceSearch, DegenerateTriangleUsesItsEdges) {
  InterfaceMesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}};
  m.addFace({0, 1, 2});  // collinear: zero area
  m.addFace({0, 2, 3});
  const SurfaceSearch search(m);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> d(-1.0, 3.0);
  for (int n = 0; n < 500; ++n) {
    const Vec3 x{d(rng), d(rng) - 1.0, 0.5 * d(rng)};
    Vec3 ref;
    const double dist = bruteDistance(search.fan(), x, ref);
    const SurfacePoint p = search.closest(x, n % 2);
    ASSERT_NEAR(p.distance, dist, 1e-12);
    ASSERT_TRUE(std::isfinite(p.bary[0]) && std::isfinite(p.bary[1]) && std::isfinite(p.bary[2]));
  }
}

TEST(SurfaceSearch, RejectsBadFaces) {
  InterfaceMesh m;
  m.name = "bad";
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.addFace({0, 1, 3});
  EXPECT_THROW(SurfaceSearch{m}, InputError);
  InterfaceMesh two;
  two.points = m.points;
  two.addFace({0, 1});
  EXPECT_THROW(SurfaceSearch{two}, InputError);
}

// ---------------------------------------------------------------------------------------------------------
// Projection

const Field kLinear = [](const Vec3& x) { return 0.3 + 1.7 * x[0] - 2.1 * x[1] + 0.9 * x[2]; };

// Three non-matching meshes of the same flat rectangle.
std::vector<InterfaceMesh> flatMeshes() {
  return {triangleGrid(7, 5, kFlat), quadGrid(13, 11, kFlat), triangleGrid(9, 8, kFlat, 0.3, 5),
          quadGrid(6, 9, kFlat, 0.3, 9)};
}

// The two linear-exact variants, for the tests that hold for both.
constexpr std::array<MassMatrix, 2> kExact{MassMatrix::Consistent, MassMatrix::Dual};

TEST(ProjectionConsistent, ReproducesLinearFieldsBothWays) {
  const auto meshes = flatMeshes();
  for (MassMatrix variant : kExact)
    for (std::size_t a = 0; a < meshes.size(); ++a)
      for (std::size_t b = 0; b < meshes.size(); ++b) {
        if (a == b) continue;
        const L2Projection h(meshes[a], meshes[b], ProjectionOptions{variant});
        ASSERT_TRUE(h.report().allMapped());
        EXPECT_LT(maxRelativeError(meshes[b], project(h, sample(meshes[a], kLinear)), kLinear), 1e-12)
            << toString(variant) << " " << a << " -> " << b;
        // Vector field, xyz-interleaved: the coordinates themselves.
        std::vector<double> xs, xt(std::size_t(3 * meshes[b].numPoints()));
        for (const Vec3& p : meshes[a].points) xs.insert(xs.end(), p.begin(), p.end());
        h.apply(xs.data(), xt.data(), 3);
        for (int i = 0; i < meshes[b].numPoints(); ++i)
          for (int k = 0; k < 3; ++k) EXPECT_NEAR(xt[3 * std::size_t(i) + k], meshes[b].points[i][k], 1e-12);
      }
}

TEST(ProjectionConservative, PreservesForceAndMomentOnFlatMeshes) {
  const auto meshes = flatMeshes();
  for (MassMatrix variant : kExact)
    for (std::size_t a = 0; a < meshes.size(); ++a)
      for (std::size_t b = 0; b < meshes.size(); ++b) {
        if (a == b) continue;
        const L2Projection h(meshes[a], meshes[b], ProjectionOptions{variant});
        const auto [ef, em] = conservationErrors(h, meshes[a], meshes[b]);
        EXPECT_LT(ef, 1e-12) << toString(variant) << " " << a << " -> " << b;
        EXPECT_LT(em, 1e-12) << toString(variant) << " " << a << " -> " << b;
        // Hᵀ is the transpose of the operator apply() uses: (H u)·f = u·(Hᵀ f).
        std::mt19937 rng(1);
        std::uniform_real_distribution<double> d(-1, 1);
        std::vector<double> u(std::size_t(meshes[a].numPoints())), f(std::size_t(meshes[b].numPoints()));
        for (double& v : u) v = d(rng);
        for (double& v : f) v = d(rng);
        std::vector<double> hu = project(h, u), htf(u.size());
        h.applyTranspose(f.data(), htf.data());
        double lhs = 0, rhs = 0;
        for (std::size_t i = 0; i < f.size(); ++i) lhs += hu[i] * f[i];
        for (std::size_t i = 0; i < u.size(); ++i) rhs += u[i] * htf[i];
        EXPECT_NEAR(lhs, rhs, 1e-12 * (std::abs(lhs) + 1));
      }
}

TEST(ProjectionLumped, RowsSumToOneAndConserveForce) {
  const auto meshes = flatMeshes();
  ProjectionOptions opt;
  opt.mass = MassMatrix::Lumped;
  const L2Projection h(meshes[2], meshes[1], opt);
  const L2Projection::SparseRows op = h.operatorMatrix();
  for (int i = 0; i < op.rows(); ++i) EXPECT_NEAR(op.row(i).sum(), 1.0, 1e-13);
  EXPECT_LT(conservationErrors(h, meshes[2], meshes[1]).first, 1e-12);
  // Lumping smooths: a linear field is only approximated (first order on irregular meshes), but closely.
  const double e = maxRelativeError(meshes[1], project(h, sample(meshes[2], kLinear)), kLinear);
  EXPECT_LT(e, 0.05);
}

TEST(ProjectionConsistent, OperatorMatrixMatchesApply) {
  const auto meshes = flatMeshes();
  const L2Projection h(meshes[0], meshes[3]);
  const L2Projection::SparseRows op = h.operatorMatrix();
  ASSERT_EQ(op.rows(), meshes[3].numPoints());
  ASSERT_EQ(op.cols(), meshes[0].numPoints());
  for (int i = 0; i < op.rows(); ++i) EXPECT_NEAR(op.row(i).sum(), 1.0, 1e-12);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> d(-1, 1);
  Eigen::VectorXd u(meshes[0].numPoints()), ut;
  for (auto& v : u) v = d(rng);
  h.apply(u, ut);
  EXPECT_LT((op * u - ut).cwiseAbs().maxCoeff(), 1e-13);
  // The exact inverse mass matrix is dense; dropping tiny entries keeps it accurate and sparser.
  const L2Projection::SparseRows dropped = h.operatorMatrix(1e-8);
  EXPECT_LT(dropped.nonZeros(), op.nonZeros());
  EXPECT_LT((dropped * u - ut).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(ProjectionDual, SparseOperatorWithRowsSummingToOne) {
  const auto meshes = flatMeshes();
  for (std::size_t b : {1, 3}) {  // quads, perturbed quads: polygon faces with centre fans
    const L2Projection dual(meshes[2], meshes[b], ProjectionOptions{MassMatrix::Dual});
    const L2Projection::SparseRows op = dual.operatorMatrix();
    EXPECT_EQ(op.nonZeros(), dual.coupling().nonZeros());
    for (int i = 0; i < op.rows(); ++i) EXPECT_NEAR(op.row(i).sum(), 1.0, 1e-13);
    // Both exact variants agree to the discretisation error, not to round-off: they are different
    // projections.
    const L2Projection consistent(meshes[2], meshes[b]);
    const Field f = [](const Vec3& x) { return std::sin(3 * x[0]) * std::cos(2 * x[1]); };
    const auto ud = project(dual, sample(meshes[2], f)), uc = project(consistent, sample(meshes[2], f));
    double diff = 0;
    for (std::size_t i = 0; i < ud.size(); ++i) diff = std::max(diff, std::abs(ud[i] - uc[i]));
    EXPECT_GT(diff, 1e-8);
    EXPECT_LT(diff, 0.05);
  }
}

// L2 errors of the projection of `f` from source to target grids refined three times.
std::vector<double> refinementErrors(const Surface& s, const Field& f, int ns0, int nt0, bool targetQuads,
                                     MassMatrix variant) {
  std::vector<double> errors;
  for (int level = 0; level < 4; ++level) {
    const int ns = ns0 << level, nt = nt0 << level;
    const InterfaceMesh src = triangleGrid(ns, ns, s, 0.2, 3);
    const InterfaceMesh dst = targetQuads ? quadGrid(nt, nt, s, 0.2, 4) : triangleGrid(nt, nt, s, 0.2, 4);
    const L2Projection h(src, dst, ProjectionOptions{variant, 0.1 / ns, 1});
    EXPECT_TRUE(h.report().allMapped()) << "level " << level;
    errors.push_back(l2Error(dst, project(h, sample(src, f)), f));
  }
  return errors;
}

void expectSecondOrder(const std::vector<double>& e) {
  for (std::size_t k = 1; k < e.size(); ++k) {
    const double rate = std::log2(e[k - 1] / e[k]);
    EXPECT_GE(rate, 1.8) << "refinement " << k << ": " << e[k - 1] << " -> " << e[k];
    EXPECT_LE(rate, 2.3) << "refinement " << k << ": " << e[k - 1] << " -> " << e[k];
  }
}

TEST(ProjectionConvergence, SecondOrderOnFlatMeshes) {
  const Field f = [](const Vec3& x) { return std::sin(3 * x[0]) * std::cos(2 * x[1]); };
  for (MassMatrix variant : kExact) {
    SCOPED_TRACE(toString(variant));
    expectSecondOrder(refinementErrors(kFlat, f, 6, 8, true, variant));
    expectSecondOrder(refinementErrors(kFlat, f, 8, 6, false, variant));
  }
}

TEST(ProjectionConvergence, SecondOrderOnCylinder) {
  const Field f = [](const Vec3& x) { return std::sin(2 * x[1] + x[0]) * std::cos(3 * x[2]); };
  for (MassMatrix variant : kExact) {
    SCOPED_TRACE(toString(variant));
    expectSecondOrder(refinementErrors(kCylinder, f, 8, 6, true, variant));
  }
}

TEST(ProjectionRatio, TenToOneBothWaysConvergesAndConserves) {
  const Field f = [](const Vec3& x) { return std::sin(2 * x[0] + x[1]); };
  for (MassMatrix variant : kExact)
    for (double ratio : {0.1, 0.3, 1.0, 3.0, 10.0}) {  // target cell size / source cell size
      SCOPED_TRACE(toString(variant));
      double previous = HUGE_VAL;
      for (int ns : {10, 20}) {
        const int nt = std::max(1, int(std::lround(ns / ratio)));
        const InterfaceMesh src = triangleGrid(ns, ns, kFlat, 0.2, 1);
        const InterfaceMesh dst = quadGrid(nt, nt, kFlat, 0.2, 2);
        const L2Projection h(src, dst, ProjectionOptions{variant});
        ASSERT_TRUE(h.report().allMapped());
        EXPECT_LT(maxRelativeError(dst, project(h, sample(src, kLinear)), kLinear), 1e-12) << ratio;
        const auto [ef, em] = conservationErrors(h, src, dst);
        EXPECT_LT(ef, 1e-12) << ratio;
        EXPECT_LT(em, 1e-12) << ratio;
        const double e = l2Error(dst, project(h, sample(src, f)), f);
        EXPECT_LT(e, 0.5 * previous) << "ratio " << ratio << ", source " << ns;
        previous = e;
      }
    }
}

TEST(ProjectionRatio, FinerQuadratureSpreadsForcesOverFineSource) {
  // Target 10x coarser than the source: with one level the transpose feeds only the source nodes near the
  // target's edge midpoints; level 10 reaches them all, and both conserve.
  const InterfaceMesh src = triangleGrid(40, 40, kFlat);
  const InterfaceMesh dst = quadGrid(4, 4, kFlat);
  for (int level : {1, 10}) {
    const L2Projection h(src, dst, ProjectionOptions{MassMatrix::Consistent, 1e-9, level});
    std::vector<double> ft(std::size_t(dst.numPoints()), 1.0), fs(std::size_t(src.numPoints()));
    h.applyTranspose(ft.data(), fs.data());
    const long loaded = std::count_if(fs.begin(), fs.end(), [](double v) { return std::abs(v) > 1e-14; });
    if (level == 1) {
      EXPECT_LT(loaded, src.numPoints() / 2);
    } else {
      EXPECT_EQ(loaded, src.numPoints());
    }
    EXPECT_LT(conservationErrors(h, src, dst).first, 1e-12);
  }
}

// Independently meshed curved patches: the discrete surfaces do not coincide (gaps of order h²/8R).
// With the gap correction (the default) linear fields, hence the moment, are exact; without it the
// moment balance is off by the gap, O(h²).
void expectCurvedConvergence(const Surface& s, MassMatrix variant, bool gapCorrection = true) {
  SCOPED_TRACE(toString(variant));
  SCOPED_TRACE(gapCorrection ? "gap correction" : "no gap correction");
  const Field f = [](const Vec3& x) { return std::sin(2 * x[1]) + x[0] * x[2]; };
  double previousError = HUGE_VAL, previousMoment = HUGE_VAL;
  for (int n : {6, 12, 24}) {
    const InterfaceMesh src = triangleGrid(n, n, s, 0.2, 1);
    const InterfaceMesh dst = quadGrid(n + n / 3, n + n / 3, s, 0.2, 2);
    const double h = 1.0 / n;
    for (bool forward : {true, false}) {
      const InterfaceMesh& a = forward ? src : dst;
      const InterfaceMesh& b = forward ? dst : src;
      const L2Projection p(a, b, ProjectionOptions{variant, 0.1 * h, 1, gapCorrection});
      ASSERT_TRUE(p.report().allMapped()) << n;
      EXPECT_GT(p.report().maxGap, 0.0);
      const double e = l2Error(b, project(p, sample(a, f)), f);
      const auto [ef, em] = conservationErrors(p, a, b);
      EXPECT_LT(ef, 1e-12);
      if (gapCorrection) {
        EXPECT_LT(em, 1e-12) << n;
        EXPECT_LT(maxRelativeError(b, project(p, sample(a, kLinear)), kLinear), 1e-12) << n;
      }
      if (forward) {
        EXPECT_LT(e, 0.3 * previousError) << n;
        if (!gapCorrection) {
          EXPECT_LT(em, 0.35 * previousMoment) << n;  // linear fields are off by the gap: O(h²)
          EXPECT_GT(em, 1e-7) << n;
        }
        EXPECT_LT(e, 0.01);
        previousError = e;
        previousMoment = em;
      }
    }
  }
}

TEST(ProjectionCurved, CylinderWithGaps) {
  for (MassMatrix variant : kExact)
    for (bool gapCorrection : {true, false}) expectCurvedConvergence(kCylinder, variant, gapCorrection);
}
TEST(ProjectionCurved, SpherePatchWithGaps) {
  for (MassMatrix variant : kExact)
    for (bool gapCorrection : {true, false}) expectCurvedConvergence(kSphere, variant, gapCorrection);
}

TEST(ProjectionUnmapped, ReportsPointsBeyondTolerance) {
  const InterfaceMesh src = triangleGrid(10, 10, kFlat);
  const InterfaceMesh dst = quadGrid(12, 10, [](double u, double v) { return Vec3{1.2 * u, 0.8 * v, 0.0}; });
  const L2Projection h(src, dst, ProjectionOptions{MassMatrix::Lumped, 1e-6, 1});
  const ProjectionReport& r = h.report();
  EXPECT_FALSE(r.allMapped());
  EXPECT_GT(r.unmappedQuadraturePoints, 0);
  EXPECT_LT(r.unmappedQuadraturePoints, r.quadraturePoints);
  ASSERT_FALSE(r.firstUnmappedPoints.empty());
  for (const UnmappedPoint& p : r.firstUnmappedPoints) {
    EXPECT_GT(p.x[0], 1.0);
    EXPECT_NEAR(p.distance, p.x[0] - 1.0, 1e-12);
  }
  ASSERT_FALSE(r.firstUnmappedNodes.empty());
  for (int i : r.firstUnmappedNodes) EXPECT_GT(dst.points[i][0], 0.9);
  // Nodes whose support lies inside the source are unaffected (the lumped operator is local).
  const std::vector<double> u = project(h, sample(src, kLinear));
  for (int i = 0; i < dst.numPoints(); ++i) {
    const Vec3& x = dst.points[i];
    if (x[0] < 0.85 && x[0] > 0.15 && x[1] > 0.1 && x[1] < 0.7) {
      EXPECT_NEAR(u[i], kLinear(x), 1e-12);
    }
  }
}

TEST(ProjectionApply, ChecksSizes) {
  const auto meshes = flatMeshes();
  const L2Projection h(meshes[0], meshes[1]);
  Eigen::VectorXd wrong(3), out;
  EXPECT_THROW(h.apply(wrong, out), std::invalid_argument);
  EXPECT_THROW(h.apply(Eigen::VectorXd::Zero(meshes[0].numPoints()), out, 2), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------------------
// Interface files

class InterfaceIOTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::random_device rd;
    dir_ = fs::temp_directory_path() / ("fsi_interface_io_" + std::to_string(rd()) + std::to_string(rd()));
    fs::create_directories(dir_ / "constant" / "polyMesh");
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  void write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / "constant" / "polyMesh" / name) << text;
  }
  static std::string header(const std::string& cls, const std::string& object,
                            const std::string& format = "ascii") {
    return "/*--------------------------------*- C++ -*----------------------------------*\\\n"
           "  =========                 |\n"
           "\\*---------------------------------------------------------------------------*/\n"
           "FoamFile\n{\n    version     2.0;\n    format      " +
           format + ";\n    arch        \"LSB;label=32;scalar=64\";\n    class       " + cls +
           ";\n    location    \"constant/polyMesh\";\n    object      " + object +
           ";\n}\n// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n\n";
  }
  // Two hexahedral cells side by side along x: 12 points, 11 faces (1 internal, 10 boundary).
  void writeTwoCells(const std::string& pointsFormat = "ascii") {
    write("points", header("vectorField", "points", pointsFormat) +
                        "12\n(\n(0 0 0)\n(1 0 0)\n(2 0 0)\n(0 1 0)\n(1 1 0)\n(2 1 0)\n"
                        "(0 0 1)\n(1 0 1)\n(2 0 1)\n(0 1 1)\n(1 1 1)\n(2 1 1)\n)\n");
    write("faces", header("faceList", "faces") +
                       "11\n(\n4(1 4 10 7)\n"                      // internal
                       "4(0 6 9 3)\n4(2 5 11 8)\n"                 // inlet, outlet
                       "4(0 1 7 6) 4(1 2 8 7)\n"                   // bottom (y = 0), two on one line
                       "4(3 9 10 4)\n4(4 10 11 5)\n"               // top (y = 1)
                       "4(0 3 4 1)\n4(1 4 5 2)\n"                  // back (z = 0)
                       "4(6 7 10 9)\n4(7 8 11 10)\n)\n// end\n");  // front (z = 1)
    write("boundary",
          header("polyBoundaryMesh", "boundary") +
              "4\n(\n    inlet\n    {\n        type patch;\n        nFaces 1;\n        startFace 1;\n"
              "    }\n    outlet { type patch; nFaces 1; startFace 2; }\n"
              "    canopy\n    {\n        type wall;\n        inGroups List<word> 1(wall);\n"
              "        nFaces 4;\n        startFace 3;\n    }\n"
              "    frontAndBack { type empty; nFaces 4; startFace 7; }\n)\n");
  }
  fs::path dir_;
};

TEST_F(InterfaceIOTest, ReadsOpenFoamPatch) {
  writeTwoCells();
  const InterfaceMesh m = readInterface(dir_.string() + ":canopy");
  ASSERT_EQ(m.numFaces(), 4);
  ASSERT_EQ(m.numPoints(), 12);
  for (int f = 0; f < 4; ++f) EXPECT_EQ(m.faceSize(f), 4);
  // Face 2 (the first on y = 1) is (3 9 10 4): (0 1 0) (0 1 1) (1 1 1) (1 1 0).
  const std::array<Vec3, 4> expected{{{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}}};
  for (int k = 0; k < 4; ++k) EXPECT_EQ(m.points[m.face(2)[k]], expected[k]);
  double area = 0;
  const FanTriangulation fan(m);
  for (int t = 0; t < fan.numTriangles(); ++t) area += fan.area(t);
  EXPECT_NEAR(area, 4.0, 1e-14);
  // Only the points of the patch, renumbered in order of first use: the inlet is (0 6 9 3).
  const InterfaceMesh inlet = readOpenFoamPatch(dir_, "inlet");
  ASSERT_EQ(inlet.numFaces(), 1);
  ASSERT_EQ(inlet.numPoints(), 4);
  EXPECT_EQ(inlet.faceNodes, (std::vector<int>{0, 1, 2, 3}));
  const std::array<Vec3, 4> inletPoints{{{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}};
  for (int k = 0; k < 4; ++k) EXPECT_EQ(inlet.points[k], inletPoints[k]);
}

TEST_F(InterfaceIOTest, WrongPatchListsAvailablePatches) {
  writeTwoCells();
  try {
    readInterface(dir_.string() + ":canopee");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("canopee"), std::string::npos) << msg;
    for (const char* p : {"inlet", "outlet", "canopy", "frontAndBack"})
      EXPECT_NE(msg.find(p), std::string::npos) << msg;
    EXPECT_NE(msg.find("boundary"), std::string::npos) << msg;
  }
}

TEST_F(InterfaceIOTest, ClearErrors) {
  auto expectError = [](const std::function<void()>& f, const std::vector<std::string>& words) {
    try {
      f();
      ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
      for (const std::string& w : words)
        EXPECT_NE(std::string(e.what()).find(w), std::string::npos) << e.what();
    }
  };
  // Missing files.
  expectError([&] { readInterface(dir_.string() + ":canopy"); }, {"points"});
  // Binary.
  writeTwoCells("binary");
  expectError([&] { readOpenFoamPatch(dir_, "canopy"); }, {"points", "binary"});
  // A face label out of range, with the line.
  writeTwoCells();
  write("faces", header("faceList", "faces") + "2\n(\n4(1 4 10 7)\n4(0 6 9 33)\n)\n");
  expectError([&] { readOpenFoamPatch(dir_, "inlet"); }, {"faces", ":18", "33"});
  // A patch beyond the face list.
  writeTwoCells();
  write("boundary",
        header("polyBoundaryMesh", "boundary") + "1\n(\n wall { type wall; nFaces 4; startFace 9; }\n)\n");
  expectError([&] { readOpenFoamPatch(dir_, "wall"); }, {"wall", "11 faces"});
  // Syntax error.
  write("boundary",
        header("polyBoundaryMesh", "boundary") + "1\n(\n wall { type wall; nFaces 4 startFace 9; }\n)\n");
  expectError([&] { readOpenFoamPatch(dir_, "wall"); }, {"boundary:", "nFaces"});
  // Not a mesh specification.
  expectError([&] { readInterface((dir_ / "nothing.txt").string()); }, {"nothing.txt"});
  expectError([&] { readInterface(dir_.string()); }, {"patch"});
}

TEST_F(InterfaceIOTest, ReadsGmshPhysicalGroup) {
  // Two unit squares, x in [0,1] ("canopy") and x in [2,3] ("other"), written by Gmsh (tests/data/gmsh).
  const fs::path file = fs::path(FSI_SOURCE_DIR) / "tests" / "data" / "gmsh" / "two_surfaces_41.msh";
  const InterfaceMesh all = readInterface(file.string());
  const InterfaceMesh canopy = readInterface(file.string() + ":canopy");
  EXPECT_GT(canopy.numFaces(), 8);
  EXPECT_LT(canopy.numFaces(), all.numFaces());
  for (const Vec3& p : canopy.points) EXPECT_LE(p[0], 1.0 + 1e-12);  // only used points kept
  try {
    readInterface(file.string() + ":nope");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("canopy"), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------------------------------------------------
// map-check

TEST(ProjectionMapCheck, ReportsAccuracyAndConservation) {
  const InterfaceMesh a = triangleGrid(12, 12, kCylinder, 0.2, 1);
  const InterfaceMesh b = quadGrid(17, 15, kCylinder, 0.2, 2);
  MapCheckOptions opt;
  // The library's full corrections (gap and defect correction, keep side, L2 evaluation) and the auto
  // variant, not the coupled run's defaults: what this test is about.
  opt.projection = ProjectionOptions{};
  opt.projection.mass = MassMatrix::Auto;
  opt.applyRepeats = 2;
  const MapCheckResult r = runMapCheck(a, b, opt);
  ASSERT_TRUE(r.allMapped());
  for (const DirectionCheck& d : r.directions) {
    EXPECT_LT(d.linear.max, 1e-12);  // the gap correction carries linear fields across the chords' gap
    EXPECT_LT(d.quadratic.max, 5e-2);
    EXPECT_LT(d.linear.rms, d.linear.max + 1e-300);
    EXPECT_GT(d.linearNearest.max, 1e-6);  // nearest-point interpolation is off by the gap
    EXPECT_LT(d.forceError, 1e-12);
    EXPECT_LT(d.momentError, 1e-12);
    EXPECT_GE(d.report.quadratureLevel, 1);
    EXPECT_EQ(d.zeroForceNodes, 0);
    // An open patch: the nodes along its edges take the gap correction's one-sided share (up to ~20 %),
    // the interior is smooth; the 5 % criterion is tested on the closed sphere (test_projection_sphere).
    EXPECT_GT(d.pressureRms, 0.0);
    EXPECT_LT(d.pressureRms, 0.1);
    EXPECT_GT(d.applySecondsScalar, 0.0);
  }
  const auto j = r.toJson();
  EXPECT_TRUE(j.at("all_mapped").get<bool>());
  EXPECT_EQ(j.at("directions").size(), 2u);
  // A target beyond the source: unmapped, said so.
  const InterfaceMesh wide = quadGrid(10, 10, [](double u, double v) { return Vec3{2 * u, v, 0.0}; });
  const InterfaceMesh narrow = quadGrid(10, 10, [](double u, double v) { return Vec3{u, v, 0.0}; });
  const MapCheckResult bad = runMapCheck(narrow, wide, opt);
  EXPECT_FALSE(bad.allMapped());
  EXPECT_NE(bad.summary().find("not mapped"), std::string::npos) << bad.summary();
}

}  // namespace
}  // namespace fsi::coupling

TEST(MassMatrixNames, OneListForEveryReader) {
  // The adapter's `projection` option offers exactly the names the projection understands, and every name
  // reads back as the mass matrix it prints as.
  using namespace fsi::coupling;
  for (const std::string& name : massMatrixNames()) {
    MassMatrix m = MassMatrix::Consistent;
    ASSERT_TRUE(massMatrixFromName(name, m)) << name;
    EXPECT_EQ(name, toString(m));
  }
  MassMatrix m = MassMatrix::Lumped;
  EXPECT_FALSE(massMatrixFromName("lumpd", m));
  EXPECT_EQ(m, MassMatrix::Lumped);
  bool found = false;
  const OptionSchema schema = couplingOptionSchema();
  for (const auto& spec : schema.specs())
    if (spec.key == "projection") {
      found = true;
      EXPECT_EQ(spec.choices, massMatrixNames());
    }
  EXPECT_TRUE(found);
}
