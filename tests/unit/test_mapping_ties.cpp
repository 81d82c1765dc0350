// The consistent transfer keeps a mirror symmetry (docs/PROJECTION.md, "Ties"). A surface symmetric about
// y = 0 with a valley or a ridge along the plane (two flanks z = k|y|, mirror-image triangulations, as a
// bulged canopy's skin meets its centre rib) and target points in the plane above it: each such point is
// exactly as far from the left flank as from the right one. A mirror-symmetric source field (u_y odd in y,
// u_x and u_z even) must arrive mirror-symmetric: u_y = 0 on the plane, and mirror pairs of targets off the
// plane get mirror values. Taking the first closest point found would give the plane's points one flank's
// value (u_y of the order of the field's slope times the foot's offset).

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "coupling/interface/SurfaceSearch.hpp"
#include "coupling/mapping/L2Projection.hpp"
#include "coupling/mapping/MappingDefaults.hpp"

namespace fsi::coupling {
namespace {

// Flanks z = k|y| over x in [0, 1], y in [-1, 1]; the y > 0 half triangulated with alternating diagonals,
// the y < 0 half its mirror image (node (i, -j) mirrors (i, j); shared nodes on y = 0).
InterfaceMesh valley(double k, int nx, int ny) {
  InterfaceMesh m;
  m.name = "valley";
  auto id = [&](int i, int j) { return (j + ny) * (nx + 1) + i; };  // j in [-ny, ny]
  for (int j = -ny; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double y = double(j) / ny;
      m.points.push_back({double(i) / nx, y, k * std::abs(y)});
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const bool alt = (i + j) % 2 == 0;
      for (int side : {1, -1}) {
        const int a = id(i, side * j), b = id(i + 1, side * j), c = id(i + 1, side * (j + 1)),
                  d = id(i, side * (j + 1));
        // the mirrored half keeps the same diagonals and reverses the order (outward normals stay up)
        if (alt) {
          side > 0 ? m.addFace({a, b, c}) : m.addFace({a, c, b});
          side > 0 ? m.addFace({a, c, d}) : m.addFace({a, d, c});
        } else {
          side > 0 ? m.addFace({a, b, d}) : m.addFace({a, d, b});
          side > 0 ? m.addFace({b, c, d}) : m.addFace({b, d, c});
        }
      }
    }
  return m;
}

// A target surface above the valley: offset `h` along z, its own (coarser, unaligned) x sampling, points on
// the plane y = 0 and mirror pairs.
InterfaceMesh above(double k, double h, int nx, int ny) {
  InterfaceMesh m;
  m.name = "fluid";
  auto id = [&](int i, int j) { return (j + ny) * (nx + 1) + i; };
  for (int j = -ny; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double y = 0.9 * double(j) / ny;
      m.points.push_back({0.05 + 0.9 * double(i) / nx, y, k * std::abs(y) + h});
    }
  for (int j = -ny; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      m.addFace({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.addFace({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

// u = (x^2 + y^2, sin(2 y) + x y, cos(x) + y^2): u_y odd in y, u_x and u_z even.
std::array<double, 3> field(const std::array<double, 3>& p) {
  return {p[0] * p[0] + p[1] * p[1], std::sin(2 * p[1]) + p[0] * p[1], std::cos(p[0]) + p[1] * p[1]};
}

void expectMirrorSymmetric(double k, double h) {
  const InterfaceMesh source = valley(k, 7, 6), target = above(k, h, 5, 4);
  ProjectionOptions opt = coupledRunProjection();
  ASSERT_EQ(opt.evaluation, ProjectionOptions::Evaluation::Pointwise);
  opt.tolerance = 1.0;
  const L2Projection map(source, target, opt);
  std::vector<double> us, ut(3 * target.points.size());
  for (const auto& p : source.points)
    for (double c : field(p)) us.push_back(c);
  map.apply(us.data(), ut.data(), 3);
  const int nx = 5, ny = 4;
  double worstPlane = 0, worstPair = 0, size = 0;
  for (int i = 0; i <= nx; ++i) {
    const std::size_t on = std::size_t(ny * (nx + 1) + i);
    worstPlane = std::max(worstPlane, std::abs(ut[3 * on + 1]));
    for (int j = 1; j <= ny; ++j) {
      const std::size_t a = std::size_t((ny + j) * (nx + 1) + i), b = std::size_t((ny - j) * (nx + 1) + i);
      const double mirror[3] = {1, -1, 1};
      for (int c = 0; c < 3; ++c) {
        worstPair = std::max(worstPair, std::abs(ut[3 * a + c] - mirror[c] * ut[3 * b + c]));
        size = std::max(size, std::abs(ut[3 * a + c]));
      }
    }
  }
  // Round-off of sums over mirror-image triangles, against field values of order 1.
  EXPECT_LT(worstPlane, 1e-12 * size) << "k " << k << ", h " << h << ": u_y on the symmetry plane";
  EXPECT_LT(worstPair, 1e-12 * size) << "k " << k << ", h " << h << ": mirror pairs";
}

TEST(MappingTies, ValleyKeepsTheMirrorSymmetry) {
  expectMirrorSymmetric(0.3,
                        0.02);  // target above a valley: the plane's points are equidistant from both flanks
}

TEST(MappingTies, RidgeKeepsTheMirrorSymmetry) {
  expectMirrorSymmetric(-0.3, -0.02);  // the same below a ridge
}

TEST(MappingTies, EquallyCloseFindsBothFlanksOnce) {
  const InterfaceMesh source = valley(0.3, 7, 6);
  const SurfaceSearch search(source);
  // above the valley: two feet, mirror images, at the same distance
  const std::array<double, 3> x{0.43, 0.0, 0.05};
  const auto ties = search.equallyClose(x, search.closest(x));
  ASSERT_EQ(ties.size(), 2u);
  EXPECT_NEAR(ties[0].point[1], -ties[1].point[1], 1e-14);
  EXPECT_GT(std::abs(ties[0].point[1]), 1e-3);
  EXPECT_NEAR(ties[0].distance, ties[1].distance, 1e-14);
  // on the valley's floor line itself the feet coincide: one point
  const std::array<double, 3> floor{0.43, 0.0, 0.0};
  EXPECT_EQ(search.equallyClose(floor, search.closest(floor)).size(), 1u);
  // off the plane: one point
  const std::array<double, 3> off{0.43, 0.2, 0.1};
  EXPECT_EQ(search.equallyClose(off, search.closest(off)).size(), 1u);
}

}  // namespace
}  // namespace fsi::coupling
