// Keeping each target point on its own side of a thin closed body (ProjectionOptions::keepSide): the
// facing-restricted closest-point search against brute force, a thin wedge whose fine mesh comes closer to
// the coarse mesh's opposite skin near the trailing edge (as a fluid skin does at a canopy's trailing edge),
// and a membrane wetted from both sides, which the rule must leave alone.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "coupling/interface/SurfaceSearch.hpp"
#include "coupling/mapping/L2Projection.hpp"

namespace fsi::coupling {
namespace {

using Vec3 = std::array<double, 3>;

Vec3 sub(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// Distance from x to triangle (a, b, c) by dense sampling of its barycentric coordinates refined around
// the best sample: independent of the search's exact projection, accurate to ~1e-9 of its size.
double sampledDistance(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& x) {
  double best = HUGE_VAL, bu = 0.0, bv = 0.0, step = 1.0 / 16;
  auto at = [&](double u, double v) {
    const double w = 1.0 - u - v;
    const Vec3 p{w * a[0] + u * b[0] + v * c[0], w * a[1] + u * b[1] + v * c[1],
                 w * a[2] + u * b[2] + v * c[2]};
    return std::sqrt(dot(sub(p, x), sub(p, x)));
  };
  for (int i = 0; i <= 16; ++i)
    for (int j = 0; i + j <= 16; ++j) {
      const double d = at(i * step, j * step);
      if (d < best) best = d, bu = i * step, bv = j * step;
    }
  for (int round = 0; round < 80; ++round) {  // pattern search, halving the step
    bool moved = false;
    for (const auto& [du, dv] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, -1}, {-1, 1}}) {
      const double u = bu + du * step, v = bv + dv * step;
      if (u < 0 || v < 0 || u + v > 1) continue;
      const double d = at(u, v);
      if (d < best) best = d, bu = u, bv = v, moved = true;
    }
    if (!moved) step *= 0.5;
  }
  return best;
}

TEST(SurfaceSearchFacing, MatchesBruteForceAmongTrianglesFacingTheWay) {
  // A wavy sheet folded over itself (a thin "trailing edge"): the lower half faces down, the upper up.
  InterfaceMesh m;
  const int n = 12;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= 2 * n; ++i) {
      const double s = double(i) / n;  // 0..2 along the fold
      const double x = s <= 1 ? s : 2 - s, y = double(j) / n;
      const double z = (s <= 1 ? -1 : 1) * 0.05 * (1 - x) + 0.02 * std::sin(4 * y);
      m.points.push_back({x, y, z});
    }
  auto id = [&](int i, int j) { return j * (2 * n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < 2 * n; ++i) {
      m.addFace({id(i, j), id(i, j + 1), id(i + 1, j + 1)});
      m.addFace({id(i, j), id(i + 1, j + 1), id(i + 1, j)});
    }
  const SurfaceSearch search(m);
  const FanTriangulation& fan = search.fan();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-0.2, 1.2), unit(-1.0, 1.0);
  int restricted = 0;
  for (int q = 0; q < 150; ++q) {
    const Vec3 x{d(rng), d(rng), 0.3 * unit(rng)};
    const Vec3 facing{0.2 * unit(rng), 0.2 * unit(rng), unit(rng) < 0 ? -1.0 : 1.0};
    double best = HUGE_VAL;
    int bestTriangle = -1;
    for (int t = 0; t < fan.numTriangles(); ++t) {
      const Vec3 a = fan.position(t, {1, 0, 0}), b = fan.position(t, {0, 1, 0}),
                 c = fan.position(t, {0, 0, 1});
      if (!(dot(cross(sub(b, a), sub(c, a)), facing) > 0.0)) continue;
      const double dist = sampledDistance(a, b, c, x);
      if (dist < best) best = dist, bestTriangle = t;
    }
    ASSERT_GE(bestTriangle, 0);
    const SurfacePoint p = search.closestFacing(x, facing, q % 3 == 0 ? q % fan.numTriangles() : -1);
    ASSERT_GE(p.triangle, 0) << "query " << q;
    EXPECT_NEAR(p.distance, best, 1e-8) << "query " << q;
    EXPECT_GT(dot(search.normal(p.triangle), facing), 0.0) << "query " << q;
    const Vec3 y = fan.position(p.triangle, p.bary);
    EXPECT_NEAR(std::sqrt(dot(sub(y, x), sub(y, x))), p.distance, 1e-12);
    if (p.distance > search.closest(x).distance + 1e-12) ++restricted;
  }
  EXPECT_GT(restricted, 15);  // the restriction did decide often (the sheet's other side was closer)
  // A zero direction is faced by nothing: no answer, and the point is unmapped.
  const SurfacePoint none = search.closestFacing({0.5, 0.5, 0.0}, {0.0, 0.0, 0.0});
  EXPECT_EQ(none.triangle, -1);
  EXPECT_FALSE(none.mapped);
}

// A closed wedge extruded over y in [0, 1]: upper skin z = τ(1 − x), lower skin z = lower(x), x in [0, 1],
// meeting at the trailing edge x = 1, a flat front face at x = 0 and polygon end caps; `nc` panels per
// chord, `ns` along the span; faces counter-clockwise about the outward normal.
struct Wedge {
  InterfaceMesh mesh;
  std::vector<int> lowerNodes;  ///< nodes of the lower skin (not the trailing edge's)
};

Wedge wedge(int nc, int ns, double tau, double bend) {
  // The section ring, counter-clockwise in the (x, z) plane: trailing edge, upper skin forwards, lower skin
  // backwards.
  std::vector<std::array<double, 2>> ring;
  std::vector<bool> lower;
  for (int i = 0; i <= nc; ++i) {
    const double x = 1.0 - double(i) / nc;
    ring.push_back({x, tau * (1 - x)});
    lower.push_back(false);
  }
  for (int i = 0; i < nc; ++i) {
    const double x = double(i) / nc;
    ring.push_back({x, -tau * (1 - x) * (1 - bend * x)});
    lower.push_back(i > 0);
  }
  const int nr = int(ring.size());
  Wedge w;
  for (int j = 0; j <= ns; ++j)
    for (int k = 0; k < nr; ++k) {
      w.mesh.points.push_back({ring[std::size_t(k)][0], double(j) / ns, ring[std::size_t(k)][1]});
      if (lower[std::size_t(k)]) w.lowerNodes.push_back(j * nr + k);
    }
  auto id = [&](int k, int j) { return j * nr + (k % nr); };
  for (int j = 0; j < ns; ++j)
    for (int k = 0; k < nr; ++k) w.mesh.addFace({id(k, j), id(k, j + 1), id(k + 1, j + 1), id(k + 1, j)});
  std::vector<int> cap0, cap1;
  for (int k = 0; k < nr; ++k) {
    cap0.push_back(id(k, 0));
    cap1.push_back(id(nr - 1 - k, ns));
  }
  w.mesh.addFace(cap0);
  w.mesh.addFace(cap1);
  return w;
}

// Enclosed volume by the divergence theorem over the fan triangles (positive for outward faces).
double enclosedVolume(const InterfaceMesh& m) {
  const FanTriangulation fan(m);
  double v = 0.0;
  for (int t = 0; t < fan.numTriangles(); ++t) {
    const Vec3 a = fan.position(t, {1, 0, 0}), b = fan.position(t, {0, 1, 0}), c = fan.position(t, {0, 0, 1});
    v += dot(a, cross(b, c)) / 6.0;
  }
  return v;
}

// Coarse source wedge (straight skins) and a fine target of the same upper skin whose lower skin bends up
// behind x = 1/bend: there the fine lower skin is closer to the coarse upper skin than to the coarse lower
// one, as a fluid skin can be at a canopy's thin trailing edge.
constexpr double kTau = 0.05, kBend = 1.1;

TEST(ProjectionKeepSide, ThinTrailingEdgeMapsOntoItsOwnSkin) {
  const Wedge source = wedge(4, 2, kTau, 0.0), target = wedge(24, 8, kTau, kBend);
  // The meshes are closed and outward: volume = section area × span (straight chords: exact).
  EXPECT_NEAR(enclosedVolume(source.mesh), kTau, 1e-14);
  // The target's lower skin g(x) = τ(1 − x)(1 − bend x) by chords of h = 1/24: the trapezoidal rule's error
  // on a quadratic is exactly h² g''/12 = h² τ bend / 6.
  const double h = 1.0 / 24, area = kTau * (1.0 - kBend / 6.0) + h * h * kTau * kBend / 6.0;
  EXPECT_NEAR(enclosedVolume(target.mesh), area, 1e-14);

  std::vector<double> z(std::size_t(source.mesh.numPoints()));
  for (int i = 0; i < source.mesh.numPoints(); ++i) z[std::size_t(i)] = source.mesh.points[std::size_t(i)][2];
  // Rows of C (the source functions seen by a target node) at the lower skin's nodes in the middle of the
  // span (far from the caps) that touch a source node of the upper skin (z > 0).
  auto crossings = [&](const L2Projection& map) {
    int rows = 0;
    for (int i : target.lowerNodes) {
      const double y = target.mesh.points[std::size_t(i)][1];
      if (y < 0.3 || y > 0.7) continue;
      bool crosses = false;
      for (L2Projection::SparseRows::InnerIterator it(map.coupling(), i); it; ++it)
        if (it.value() != 0.0 && z[std::size_t(it.col())] > 1e-12) crosses = true;
      rows += crosses;
    }
    return rows;
  };
  ProjectionOptions off;
  off.quadratureLevel = 1;
  off.gapCorrection = false;
  off.keepSide = false;
  const L2Projection plain(source.mesh, target.mesh, off);
  EXPECT_GT(crossings(plain), 0) << "the test set-up must put target points nearer the opposite skin";

  ProjectionOptions on = off;
  on.keepSide = true;
  const L2Projection sided(source.mesh, target.mesh, on);
  const ProjectionReport& r = sided.report();
  EXPECT_TRUE(r.oneSided);
  EXPECT_GE(r.facingShare, kOneSidedShare);
  EXPECT_GT(r.residedPoints, 0);
  EXPECT_EQ(r.turnedPoints, 0);
  EXPECT_TRUE(r.allMapped());
  EXPECT_EQ(crossings(sided), 0);
  // The moved points' new gap: the fine lower skin's height above the coarse one, τ(1 − x) bend x, at most
  // τ bend / 4 at x = 1/2 and smaller than that behind x = 1/bend.
  EXPECT_LE(r.maxResidedGap, kTau * kBend * (1 - 1 / kBend) + 1e-12);

  // Still a projection: constants exact at every node, and Hᵀ conserves a random force exactly.
  std::vector<double> ones(std::size_t(source.mesh.numPoints()), 1.0),
      out(std::size_t(target.mesh.numPoints()));
  sided.apply(ones.data(), out.data());
  for (double v : out) ASSERT_NEAR(v, 1.0, 1e-12);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> f(-1.0, 1.0);
  std::vector<double> ft(3 * out.size()), fs(3 * ones.size());
  for (double& v : ft) v = f(rng);
  sided.applyTranspose(ft.data(), fs.data(), 3);
  for (int k = 0; k < 3; ++k) {
    double a = 0.0, b = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < out.size(); ++i)
      a += ft[3 * i + std::size_t(k)], scale += std::abs(ft[3 * i + std::size_t(k)]);
    for (std::size_t i = 0; i < ones.size(); ++i) b += fs[3 * i + std::size_t(k)];
    EXPECT_NEAR(a, b, 1e-13 * scale);
  }
}

TEST(ProjectionKeepSide, GapCorrectionFitsEachSkinOnItsOwn) {
  // A field that has a kink at the trailing edge, as a displacement does when one skin bulges and the other
  // does not: f = z on the upper skin, 0 on the lower. The gap correction's gradient of a lower-skin
  // triangle must come from the lower skin alone; fitted across the edge it would carry the upper skin's
  // ∂f/∂z = 1 over the gap between the bent fine lower skin and the coarse one.
  const Wedge source = wedge(4, 2, kTau, 0.0), target = wedge(24, 8, kTau, kBend);
  std::vector<double> f(std::size_t(source.mesh.numPoints())), out(std::size_t(target.mesh.numPoints()));
  for (int i = 0; i < source.mesh.numPoints(); ++i)
    f[std::size_t(i)] = std::max(source.mesh.points[std::size_t(i)][2], 0.0);
  ProjectionOptions opt;
  opt.mass = MassMatrix::Lumped;  // each node's value from its own support only
  opt.quadratureLevel = 2;
  opt.gapCorrection = true;
  opt.keepSide = true;
  const L2Projection h(source.mesh, target.mesh, opt);
  ASSERT_GT(h.report().gapStencilEntries, 0);
  h.apply(f.data(), out.data());
  int checked = 0;
  for (int i : target.lowerNodes) {
    const double y = target.mesh.points[std::size_t(i)][1];
    if (y < 0.3 || y > 0.7) continue;
    EXPECT_EQ(out[std::size_t(i)], 0.0) << "node at x = " << target.mesh.points[std::size_t(i)][0];
    ++checked;
  }
  EXPECT_GT(checked, 40);
}

TEST(ProjectionKeepSide, MembraneWettedFromBothSidesIsLeftAlone) {
  // One membrane (the structure) and its two fluid faces, 1 mm above and below, facing away from it (as
  // OpenFOAM's baffle patches do): half the fluid faces the membrane's normal, half against it.
  InterfaceMesh membrane, fluid;
  const int n = 6, m = 18;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) membrane.points.push_back({double(i) / n, double(j) / n, 0.0});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i;
      membrane.addFace({a, a + 1, a + n + 2, a + n + 1});
    }
  for (double side : {1.0, -1.0}) {
    const int base = fluid.numPoints();
    for (int j = 0; j <= m; ++j)
      for (int i = 0; i <= m; ++i) fluid.points.push_back({double(i) / m, double(j) / m, 1e-3 * side});
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const int a = base + j * (m + 1) + i;
        if (side > 0)
          fluid.addFace({a, a + 1, a + m + 2, a + m + 1});
        else
          fluid.addFace({a, a + m + 1, a + m + 2, a + 1});
      }
  }
  ProjectionOptions opt;
  opt.keepSide = true;
  const L2Projection h(membrane, fluid, opt);
  EXPECT_NEAR(h.report().facingShare, 0.5, 1e-12);
  EXPECT_FALSE(h.report().oneSided);
  EXPECT_EQ(h.report().residedPoints, 0);
  // Both fluid faces take the membrane's field: a linear one is reproduced on each.
  std::vector<double> us(std::size_t(membrane.numPoints())), ut(std::size_t(fluid.numPoints()));
  for (int i = 0; i < membrane.numPoints(); ++i)
    us[std::size_t(i)] = 0.2 + membrane.points[std::size_t(i)][0] - 0.7 * membrane.points[std::size_t(i)][1];
  h.apply(us.data(), ut.data());
  for (int i = 0; i < fluid.numPoints(); ++i)
    ASSERT_NEAR(ut[std::size_t(i)],
                0.2 + fluid.points[std::size_t(i)][0] - 0.7 * fluid.points[std::size_t(i)][1], 1e-12);
}

}  // namespace
}  // namespace fsi::coupling
