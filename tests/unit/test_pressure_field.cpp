// pressure_field: another code's pressure mapped onto the structure's triangles (one-way FSI).
//  * VTK surface: a linear field on a finer, non-matching surface of the same curved shape gives the analytic
//    resultant and moment within discretisation error (falling with the mesh), and the integral of the
//    pressure (the resultant on a flat surface) is carried over to round-off: the transfer is conservative.
//  * CSV point cloud: inverse-distance interpolation converges to a smooth field as the cloud is refined, and
//    refuses triangles farther than the tolerance from every cloud point.
//  * Bad files: every error names the file and the line (column, keyword).
//  * The scene effect: registered from the coupling side, sign (pushes against the normal, as `pressure` with
//    the opposite value), relative path, dead and follower loads, located errors.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "TestScenes.hpp"
#include "coupling/effects/CouplingEffects.hpp"
#include "coupling/effects/PointCloudInterpolation.hpp"
#include "coupling/effects/PressureFieldFiles.hpp"
#include "coupling/effects/SurfacePressureMapping.hpp"
#include "coupling/interface/SurfaceSearch.hpp"
#include "structure/effects/PressureDistribution.hpp"
#include "structure/model/Error.hpp"
#include "structure/parafoil/ParafoilGeometry.hpp"

using namespace fsi::coupling;
using fsi::InputError;
using fsi::structure::ForceContext;
using fsi::structure::PressureDistribution;
using fsi::structure::TimeFunction;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A cylinder panel of radius R about the x axis: x in [0, L], θ in [θ0, θ1], point (x, R sin θ, R cos θ),
// outward normal (0, sin θ, cos θ). nx × nt cells; quads as polygons, or triangles (diagonals alternating).
constexpr double R = 2.0, L = 1.0, T0 = 0.1, T1 = 0.9;
std::array<double, 3> panelPoint(double x, double t) {
  return {x, R * std::sin(t), R * std::cos(t)};
}

InterfaceMesh panel(int nx, int nt, bool quads, double shift = 0.0) {
  InterfaceMesh m;
  m.name = "panel";
  for (int j = 0; j <= nt; ++j)
    for (int i = 0; i <= nx; ++i) {
      // Interior points shifted along x by a fraction of a cell: not matching any other mesh's nodes.
      const double s = (i > 0 && i < nx) ? shift * std::sin(1.7 * j) / nx : 0.0;
      m.points.push_back(panelPoint(L * i / nx + s, T0 + (T1 - T0) * j / nt));
    }
  auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  // (x, θ) counter-clockwise about +x × +θ = outward normal? ∂r/∂x × ∂r/∂θ = (1,0,0) × (0, R cos, −R sin)
  // = (0, R sin, R cos): outward. So (i,j) → (i+1,j) → (i+1,j+1) is counter-clockwise about the outward
  // normal.
  for (int j = 0; j < nt; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (quads) {
        m.addFace({a, b, c, d});
      } else if ((i + j) % 2 == 0) {
        m.addFace({a, b, c});
        m.addFace({a, c, d});
      } else {
        m.addFace({a, b, d});
        m.addFace({b, c, d});
      }
    }
  return m;
}

constexpr double kA = 80.0, kB = -30.0, kC = 25.0;  // p = a + b x + c z  [Pa]
double linearP(const std::array<double, 3>& p) {
  return kA + kB * p[0] + kC * p[2];
}

struct Resultant {
  std::array<double, 3> force{}, moment{};
};

// −∫ p n dA and −∫ r × p n dA on the exact cylinder panel, in closed form.
Resultant analytic() {
  const double iSin = std::cos(T0) - std::cos(T1), iCos = std::sin(T1) - std::sin(T0);
  const double iCosSin = (std::sin(T1) * std::sin(T1) - std::sin(T0) * std::sin(T0)) / 2;
  const double iCos2 = (T1 - T0) / 2 + (std::sin(2 * T1) - std::sin(2 * T0)) / 4;
  const double a1 = kA * L + kB * L * L / 2, b1 = kA * L * L / 2 + kB * L * L * L / 3;
  Resultant r;
  r.force = {0.0, -R * (a1 * iSin + kC * R * L * iCosSin), -R * (a1 * iCos + kC * R * L * iCos2)};
  // r × n = (0, −x cos θ, x sin θ)
  r.moment = {0.0, R * (b1 * iCos + kC * R * L * L / 2 * iCos2),
              -R * (b1 * iSin + kC * R * L * L / 2 * iCosSin)};
  return r;
}

// The nodal forces of per-triangle pressures (positive along the normal) on mesh `m`, summed.
Resultant resultantOf(const InterfaceMesh& m, const std::vector<double>& along, bool dead) {
  std::vector<double> X;
  for (const auto& p : m.points) X.insert(X.end(), p.begin(), p.end());
  std::vector<int> conn(m.faceNodes.begin(), m.faceNodes.end());
  const PressureDistribution e =
      dead ? PressureDistribution::dead("skin", conn, along, TimeFunction::constant(), X)
           : PressureDistribution("skin", conn, along, TimeFunction::constant());
  std::vector<double> f(X.size(), 0.0), fint(X.size(), 0.0);
  ForceContext ctx;
  ctx.x = X.data();
  ctx.fint = fint.data();
  ctx.fext = f.data();
  e.addForces(ctx);
  Resultant r;
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const double* x = &X[3 * i];
    const double* g = &f[3 * i];
    for (int k = 0; k < 3; ++k) r.force[std::size_t(k)] += g[k];
    r.moment[0] += x[1] * g[2] - x[2] * g[1];
    r.moment[1] += x[2] * g[0] - x[0] * g[2];
    r.moment[2] += x[0] * g[1] - x[1] * g[0];
  }
  return r;
}

double norm(const std::array<double, 3>& v) {
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}
double relError(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return norm({a[0] - b[0], a[1] - b[1], a[2] - b[2]}) / norm(b);
}

std::string nodeName(int i) {
  return "node " + std::to_string(i);
}

SurfaceField sampled(InterfaceMesh mesh) {
  SurfaceField s{std::move(mesh), {}};
  for (const auto& p : s.mesh.points) s.values.push_back(linearP(p));
  return s;
}

double sumPA(const InterfaceMesh& m, const std::vector<double>& p) {
  const fsi::coupling::FanTriangulation fan(m);
  double s = 0;
  for (int t = 0; t < fan.numTriangles(); ++t)
    s += fan.area(t) * p[std::size_t(fan.triangleFace[std::size_t(t)])];
  return s;
}

}  // namespace

TEST(PressureField, LinearFieldOnAFinerCurvedSurfaceGivesTheAnalyticResultant) {
  const Resultant exact = analytic();
  double previousForce = 1e300, previousMoment = 1e300;
  for (int n : {6, 12}) {
    const InterfaceMesh skin = panel(n, n, false);
    // The file: quads, about 2.3 times finer, nodes shifted: nothing matches the skin's nodes.
    const SurfaceField source = sampled(panel(int(2.3 * n) + 1, int(2.3 * n) + 2, true, 0.3));
    const std::vector<double> p = conservativeTrianglePressure(skin, source, 0.05, nodeName);
    // Conservative: the integral of the pressure is carried over to round-off.
    EXPECT_NEAR(sumPA(skin, p), surfaceIntegral(source), 1e-12 * std::abs(surfaceIntegral(source))) << n;
    std::vector<double> along(p.size());
    for (std::size_t e = 0; e < p.size(); ++e) along[e] = -p[e];  // pushes against the outward normal
    for (bool dead : {false, true}) {
      const Resultant r = resultantOf(skin, along, dead);
      const double ef = relError(r.force, exact.force), em = relError(r.moment, exact.moment);
      EXPECT_LT(ef, 0.01) << n;
      EXPECT_LT(em, 0.01) << n;
      if (!dead) {
        EXPECT_LT(ef, previousForce / 3) << n;  // second order in the mesh size
        EXPECT_LT(em, previousMoment / 3) << n;
        previousForce = ef, previousMoment = em;
      }
    }
  }
}

TEST(PressureField, FlatSurfaceResultantIsTheSourcesToRoundOff) {
  // On a plane the resultant is n ∫ p dA: the conservative transfer keeps it exactly, for a non-matching
  // source finer or coarser than the triangles.
  auto plate = [](int nx, int ny, bool quads) {
    InterfaceMesh m;
    m.name = "plate";
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) m.points.push_back({1.0 * i / nx, 0.5 * j / ny, 0.0});
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int a = j * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;
        if (quads) {
          m.addFace({a, b, c, d});
        } else {
          m.addFace({a, b, c});
          m.addFace({a, c, d});
        }
      }
    return m;
  };
  const InterfaceMesh skin = plate(8, 5, false);
  for (const InterfaceMesh& file : {plate(19, 11, true), plate(3, 2, true)}) {
    SurfaceField source{file, {}};
    for (const auto& x : file.points) source.values.push_back(kA + kB * x[0] + kC * x[1] * x[1]);
    const std::vector<double> p = conservativeTrianglePressure(skin, source, 1e-6, nodeName);
    std::vector<double> along(p.size());
    for (std::size_t e = 0; e < p.size(); ++e) along[e] = -p[e];
    for (bool dead : {false, true}) {
      const Resultant r = resultantOf(skin, along, dead);
      EXPECT_NEAR(r.force[2], -surfaceIntegral(source), 1e-12 * std::abs(surfaceIntegral(source)));
      EXPECT_NEAR(r.force[0], 0.0, 1e-12);
      EXPECT_NEAR(r.force[1], 0.0, 1e-12);
    }
  }
}

TEST(PressureField, SurfaceThatDoesNotCoverTheTrianglesIsRefused) {
  const InterfaceMesh skin = panel(6, 6, false);
  // Only the first half of the panel in θ.
  InterfaceMesh half = panel(10, 10, true);
  for (auto& p : half.points) {
    const double t = std::atan2(p[1], p[2]);
    const auto q = panelPoint(p[0], T0 + 0.5 * (t - T0));
    p = q;
  }
  try {
    conservativeTrianglePressure(skin, sampled(half), 0.05, nodeName);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("does not cover node"), std::string::npos) << e.what();
  }
  // A file reaching beyond the triangles (a longer panel) is refused too: its force would be lost.
  InterfaceMesh longer = panel(10, 10, true);
  for (auto& p : longer.points) p[0] *= 1.5;
  try {
    conservativeTrianglePressure(skin, sampled(longer), 0.05, nodeName);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("farther than the tolerance"), std::string::npos) << e.what();
  }
}

TEST(PressureField, PointCloudInterpolationConvergesAsTheCloudIsRefined) {
  auto field = [](const std::array<double, 3>& x) {
    return 100.0 * std::sin(2.0 * x[0]) + 40.0 * x[1] * x[1];
  };
  std::vector<std::array<double, 3>> queries;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 10; ++j) queries.push_back({(i + 0.5) / 20.0, 0.5 * (j + 0.5) / 10.0, 0.0});
  std::mt19937 rng(1234);
  std::uniform_real_distribution<double> ux(-0.02, 1.02), uy(-0.01, 0.51);
  double previous = 1e300;
  for (int n : {300, 1200, 4800, 19200}) {
    std::vector<std::array<double, 3>> pts;
    std::vector<double> vals;
    for (int i = 0; i < n; ++i) {
      pts.push_back({ux(rng), uy(rng), 0.0});
      vals.push_back(field(pts.back()));
    }
    const CloudInterpolation r = interpolateCloud(pts, vals, queries, 4, 0.2);
    ASSERT_EQ(r.firstFailed, -1);
    double err = 0;
    for (std::size_t q = 0; q < queries.size(); ++q)
      err = std::max(err, std::abs(r.values[q] - field(queries[q])));
    EXPECT_LT(err, 0.75 * previous) << n;  // O(h): h halves with every factor 4 in points
    previous = err;
  }
  EXPECT_LT(previous, 2.0);  // of a field of amplitude ~100 Pa
}

TEST(PressureField, PointCloudSearchFindsTheTrueNearestPoints) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<std::array<double, 3>> pts(500);
  for (auto& p : pts) p = {u(rng), u(rng), 0.1 * u(rng)};
  const PointCloudSearch search(pts);
  std::vector<std::pair<double, int>> got;
  for (int q = 0; q < 100; ++q) {
    const std::array<double, 3> x{1.5 * u(rng), 1.5 * u(rng), u(rng)};
    std::vector<std::pair<double, int>> all;
    for (int i = 0; i < int(pts.size()); ++i)
      all.push_back(
          {std::sqrt(std::pow(pts[std::size_t(i)][0] - x[0], 2) + std::pow(pts[std::size_t(i)][1] - x[1], 2) +
                     std::pow(pts[std::size_t(i)][2] - x[2], 2)),
           i});
    std::sort(all.begin(), all.end());
    search.nearest(x, 5, 1e300, got);
    ASSERT_EQ(got.size(), 5u);
    for (int k = 0; k < 5; ++k) EXPECT_EQ(got[std::size_t(k)].second, all[std::size_t(k)].second) << q;
    search.nearest(x, 5, all[2].first * 1.0000001, got);
    EXPECT_EQ(got.size(), 3u);  // the radius limits the list
  }
}

TEST(PressureField, CloudFartherThanTheToleranceIsReported) {
  const std::vector<std::array<double, 3>> pts{{0, 0, 0}, {1, 0, 0}};
  const CloudInterpolation r = interpolateCloud(pts, {1.0, 2.0}, {{0.1, 0, 0}, {3.0, 0, 0}}, 2, 0.5);
  EXPECT_EQ(r.firstFailed, 1);
  EXPECT_DOUBLE_EQ(r.failedDistance, 2.0);
}

// ---------------------------------------------------------------- bad files

namespace {

std::filesystem::path writeFile(const std::string& name, const std::string& text) {
  const auto dir = fsi::test::outDir("pressure-field-files");
  std::filesystem::create_directories(dir);
  const auto f = dir / name;
  std::ofstream(f) << text;
  return f;
}

std::string csvError(const std::string& text, const std::string& column = "p") {
  const auto f = writeFile("cloud.csv", text);
  try {
    readPointCloudCsv(f, column);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string vtkError(const std::string& text, const std::string& field = "p") {
  const auto f = writeFile("surface.vtk", text);
  try {
    readVtkSurface(f, field);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

bool has(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

const std::string kVtk = R"(# vtk DataFile Version 3.0
a square
ASCII
DATASET POLYDATA
POINTS 4 float
0 0 0  1 0 0
1 1 0  0 1 0
POLYGONS 1 5
4 0 1 2 3
POINT_DATA 4
SCALARS p double 1
LOOKUP_TABLE default
1 2 3 4
)";

}  // namespace

TEST(PressureFieldFiles, ReadsGoodFiles) {
  const PointCloud c = readPointCloudCsv(
      writeFile("ok.csv",
                "\xEF\xBB\xBFX, y ,z,cp,extra\r\n# from a panel code\n0,0,0,1.5,a\n\n1,2,3,-0.5,b\n"),
      "cp");
  ASSERT_EQ(c.points.size(), 2u);
  EXPECT_DOUBLE_EQ(c.points[1][2], 3.0);
  EXPECT_DOUBLE_EQ(c.values[1], -0.5);
  const SurfaceField s = readVtkSurface(writeFile("ok.vtk", kVtk), "p");
  EXPECT_EQ(s.mesh.numFaces(), 1);
  EXPECT_EQ(s.mesh.faceSize(0), 4);
  EXPECT_DOUBLE_EQ(s.values[3], 4.0);
  // SCALARS without its optional component count (the values follow on the next lines).
  const SurfaceField s2 = readVtkSurface(
      writeFile("ok2.vtk", fsi::test::replaced(kVtk, "SCALARS p double 1\nLOOKUP_TABLE default\n1",
                                               "SCALARS p double\nLOOKUP_TABLE default\n1")),
      "p");
  EXPECT_DOUBLE_EQ(s2.values[0], 1.0);
  // Version 5.1 cell lists (OFFSETS/CONNECTIVITY), the field in a FIELD block after other attributes, a
  // strip.
  const std::string v51 = R"(# vtk DataFile Version 5.1
vtk output
ASCII
DATASET POLYDATA
POINTS 4 float
0 0 0 1 0 0 1 1 0 0 1 0
METADATA
INFORMATION 0

TRIANGLE_STRIPS 2 4
OFFSETS vtktypeint64
0 4
CONNECTIVITY vtktypeint64
0 1 3 2
POINT_DATA 4
NORMALS n float
0 0 1 0 0 1 0 0 1 0 0 1
FIELD FieldData 2
rho 1 4 double
1 1 1 1
p 1 4 double
5 6 7 8
)";
  const SurfaceField s51 = readVtkSurface(writeFile("ok51.vtk", v51), "p");
  EXPECT_EQ(s51.mesh.numFaces(), 2);
  EXPECT_DOUBLE_EQ(s51.values[2], 7.0);
  // The strip keeps one orientation: both triangles' normals +z.
  for (int f = 0; f < 2; ++f) {
    const int* v = s51.mesh.face(f);
    const auto &a = s51.mesh.points[std::size_t(v[0])], &b = s51.mesh.points[std::size_t(v[1])],
               &c2 = s51.mesh.points[std::size_t(v[2])];
    EXPECT_GT((b[0] - a[0]) * (c2[1] - a[1]) - (b[1] - a[1]) * (c2[0] - a[0]), 0.0) << f;
  }
}

TEST(PressureFieldFiles, CsvErrorsNameFileLineAndColumn) {
  std::string e = csvError("x,y,z,cp\n0,0,0,1\n");
  EXPECT_TRUE(has(e, "cloud.csv:1: the header has no column 'p'") && has(e, "columns: x, y, z, cp")) << e;
  e = csvError("x,y,p\n0,0,0\n");
  EXPECT_TRUE(has(e, "cloud.csv:1:") && has(e, "'z'")) << e;
  e = csvError("x,y,z,p\n0,0,0,1\n0,0,0,nan\n");
  EXPECT_TRUE(has(e, "cloud.csv:3: column 'p': 'nan' is not a finite number")) << e;
  e = csvError("x,y,z,p\n0,0,0,1\n0,1e999,0,1\n");
  EXPECT_TRUE(has(e, "cloud.csv:3: column 'y': '1e999'")) << e;
  e = csvError("x,y,z,p\n0,0,0\n");
  EXPECT_TRUE(has(e, "cloud.csv:2: 3 values, the header (line 1) has 4 columns")) << e;
  e = csvError("x,y,z,p\n0,0,0,1\x01\xff\n");
  EXPECT_TRUE(has(e, "cloud.csv:2: column 'p': '1\\x01\\xFF' is not a finite number"))
      << e;  // bytes shown escaped
  e = csvError("x,y,z,p\n0,0,0,1x\n");
  EXPECT_TRUE(has(e, "cloud.csv:2: column 'p': '1x'")) << e;
  e = csvError("x,y,z,p,x\n");
  EXPECT_TRUE(has(e, "cloud.csv:1: column 'x' given twice")) << e;
  e = csvError("x,y,z,p\n");
  EXPECT_TRUE(has(e, "cloud.csv:1: no data rows")) << e;
  e = csvError("");
  EXPECT_TRUE(has(e, "cloud.csv: empty file")) << e;
}

TEST(PressureFieldFiles, VtkErrorsNameFileAndLine) {
  auto with = [](const std::string& from, const std::string& to) {
    return fsi::test::replaced(kVtk, from, to);
  };
  std::string e = vtkError(with("ASCII", "BINARY"));
  EXPECT_TRUE(has(e, "surface.vtk:3: 'BINARY': only ASCII")) << e;
  e = vtkError(with("# vtk", "# vtkk"));
  EXPECT_TRUE(has(e, "surface.vtk:1: not a legacy VTK file")) << e;
  e = vtkError(with("POLYDATA", "UNSTRUCTURED_GRID"));
  EXPECT_TRUE(has(e, "surface.vtk:4: DATASET UNSTRUCTURED_GRID: only POLYDATA")) << e;
  e = vtkError(with("POINTS 4", "POINTS 4000000000"));
  EXPECT_TRUE(has(e, "surface.vtk:5: POINTS count: 4000000000 is more than the rest of the file can hold"))
      << e;
  e = vtkError(with("1 1 0  0 1 0", "1 1 0  0 nan 0"));
  EXPECT_TRUE(has(e, "surface.vtk:7: POINTS coordinate: 'nan' is not a finite number")) << e;
  e = vtkError(with("4 0 1 2 3", "4 0 1 2 7"));
  EXPECT_TRUE(has(e, "surface.vtk:9: POLYGONS point index: '7' is not an integer in [0, 3]")) << e;
  e = vtkError(with("POLYGONS 1 5", "POLYGONS 100000000 5"));
  EXPECT_TRUE(
      has(e, "surface.vtk:8: POLYGONS cell count: 100000000 is more than the rest of the file can hold"))
      << e;
  e = vtkError(with("POLYGONS 1 5", "POLYGONS 1 6"));
  EXPECT_TRUE(has(e, "surface.vtk:") && has(e, "POLYGONS")) << e;
  e = vtkError(with("POLYGONS 1 5\n4 0 1 2 3", "POLYGONS 1 3\n2 0 1"));
  EXPECT_TRUE(has(e, "surface.vtk:8: POLYGONS: a polygon with 2 points")) << e;
  e = vtkError(with("1 2 3 4", "1 2 inf 4"));
  EXPECT_TRUE(has(e, "surface.vtk:13: field 'p' value: 'inf' is not a finite number")) << e;
  e = vtkError(with("1 2 3 4\n", "1 2 3\n"));
  EXPECT_TRUE(has(e, "surface.vtk:") && has(e, "the file ends where field 'p' value was expected")) << e;
  e = vtkError(kVtk, "pressure");
  EXPECT_TRUE(has(e, "surface.vtk: no POINT_DATA field 'pressure'") && has(e, "point data: p")) << e;
  e = vtkError(with("POINT_DATA 4", "CELL_DATA 1\nSCALARS p double\nLOOKUP_TABLE default\n9\nPOINT_DATA 4"),
               "p");
  EXPECT_TRUE(e.empty()) << e;  // a cell-data array of the same name is skipped
  e = vtkError(with("POINT_DATA 4\nSCALARS p",
                    "CELL_DATA 1\nSCALARS p double\nLOOKUP_TABLE default\n9\n"
                    "POINT_DATA 4\nSCALARS q"));
  EXPECT_TRUE(has(e, "no POINT_DATA field 'p' (it is CELL_DATA")) << e;
  e = vtkError(with("POINT_DATA 4", "POINT_DATA 5"));
  EXPECT_TRUE(has(e, "surface.vtk:10: POINT_DATA 5: the file has 4 points")) << e;
  e = vtkError(with("1 2 3 4\n", "1 2 3 4\nWHATEVER\n"));
  EXPECT_TRUE(has(e, "surface.vtk:14: unexpected 'WHATEVER'")) << e;
  e = vtkError(with("SCALARS p double 1", "SCALARS p double 3"));
  EXPECT_TRUE(has(e, "field 'p' has 3 components")) << e;
  e = vtkError(with("POLYGONS 1 5\n4 0 1 2 3\n", ""));
  EXPECT_TRUE(has(e, "surface.vtk: no POLYGONS or TRIANGLE_STRIPS")) << e;
}

// ---------------------------------------------------------------- the scene effect

namespace {

// The drum scene (1 m square film, normal +z) in a folder of its own, with `effects` added.
std::string drumWith(const std::string& effects) {
  return fsi::test::drumScene("effects:\n" + effects + "time: {end: 1.0e-3}\n");
}

std::vector<double> sceneForces(const std::string& yaml, const std::filesystem::path& dir, double t = 0.0) {
  const fsi::structure::Scene s = fsi::structure::loadSceneFromString(yaml, (dir / "case.yaml").string());
  const auto& X = s.model->nodes.X;
  std::vector<double> f(X.size(), 0.0), fint(X.size(), 0.0);
  ForceContext ctx;
  ctx.time = t;
  ctx.x = X.data();
  ctx.fint = fint.data();
  ctx.fext = f.data();
  for (const auto& e : s.effects) e->addForces(ctx);
  return f;
}

}  // namespace

TEST(PressureFieldEffect, IsRegisteredFromTheCouplingSide) {
  registerCouplingEffects();
  registerCouplingEffects();  // idempotent
  int n = 0;
  for (const auto& k : fsi::structure::effectKinds()) n += k.name == "pressure_field";
  EXPECT_EQ(n, 1);
  const std::string e =
      fsi::test::sceneError(drumWith("  pressure_feld: {triangles: sheet, file: a.vtk}\n"), "case.yaml");
  EXPECT_TRUE(has(e, "did you mean 'pressure_field'")) << e;
  EXPECT_THROW(
      fsi::structure::registerEffectKind({"pressure", {}, "", false, "", pressureFieldEffect().build}),
      std::logic_error);
}

TEST(PressureFieldEffect, PushesAgainstTheNormalLikePressureWithTheOppositeValue) {
  registerCouplingEffects();
  const auto dir = fsi::test::outDir("pressure-field-scene");
  std::filesystem::create_directories(dir / "cfd");
  {
    std::ofstream csv(dir / "cfd" / "cloud.csv");
    csv << "x,y,z,cp\n";
    for (int i = 0; i <= 20; ++i)
      for (int j = 0; j <= 20; ++j) csv << (i / 20.0 - 0.5) << "," << (j / 20.0 - 0.5) << ",0,0.5\n";
  }
  {
    std::ofstream vtk(dir / "cfd" / "surface.vtk");
    vtk << "# vtk DataFile Version 3.0\nplane\nASCII\nDATASET POLYDATA\nPOINTS 4 double\n"
           "-0.5 -0.5 0 0.5 -0.5 0 0.5 0.5 0 -0.5 0.5 0\nPOLYGONS 1 5\n4 0 1 2 3\nPOINT_DATA 4\n"
           "SCALARS pressure double\nLOOKUP_TABLE default\n30 30 30 30\n";
  }
  const auto reference =
      sceneForces(drumWith("  pressure: {triangles: sheet, value: -30.0, function: 2.0}\n"), dir);
  double fz = 0;
  for (std::size_t i = 2; i < reference.size(); i += 3) fz += reference[i];
  EXPECT_NEAR(fz, -60.0, 1e-9);  // 30 Pa · 2 on 1 m², into the +z side
  // A constant field: the cloud's interpolation is exact node by node; the projection from the one-quad
  // surface keeps the resultant to round-off, and the nodal forces to the quadrature error of a source much
  // coarser than the triangles (the bends of their shape functions inside its faces).
  const struct {
    std::string effect;
    double nodalTolerance;
  } cases[] = {
      {"  pressure_field: {triangles: sheet, file: cfd/cloud.csv, quantity: cp, dynamic_pressure: 60.0, "
       "function: 2.0}\n",
       1e-9},
      {"  pressure_field: {triangles: sheet, file: cfd/surface.vtk, field: pressure, scale: 2.0, follower: "
       "false}\n",
       0.02 * 0.625},
      {"  pressure_field: {triangles: sheet, file: cfd/surface.vtk, field: pressure, scale: 2.0, projection: "
       "consistent}\n",
       1e-9},
      {"  pressure_field:\n    - {triangles: sheet, file: cfd/surface.vtk, field: pressure}\n"
       "    - {triangles: sheet, file: cfd/surface.vtk, field: pressure, tolerance: 0.01}\n",
       0.02 * 0.625}};
  for (const auto& c : cases) {
    const auto f = sceneForces(drumWith(c.effect), dir);
    ASSERT_EQ(f.size(), reference.size());
    double sum[3] = {0, 0, 0};
    for (std::size_t i = 0; i < f.size(); ++i) {
      EXPECT_NEAR(f[i], reference[i], c.nodalTolerance) << c.effect << " dof " << i;
      sum[i % 3] += f[i];
    }
    EXPECT_NEAR(sum[2], -60.0, 1e-12 * 60) << c.effect;
    EXPECT_NEAR(sum[0], 0.0, 1e-12) << c.effect;
    EXPECT_NEAR(sum[1], 0.0, 1e-12) << c.effect;
  }
}

TEST(PressureFieldEffect, SceneErrorsAreLocated) {
  registerCouplingEffects();
  const auto dir = fsi::test::outDir("pressure-field-errors");
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "half.csv") << "x,y,z,p\n-0.5,-0.5,0,1\n-0.5,0.5,0,1\n0,-0.5,0,1\n0,0.5,0,1\n";
  auto err = [&](const std::string& fx) {
    try {
      sceneForces(drumWith(fx), dir);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  std::string e = err("  pressure_field: {triangles: sheet, file: missing.vtk}\n");
  EXPECT_TRUE(has(e, "case.yaml:10:") && has(e, "effects.pressure_field.file") &&
              has(e, "missing.vtk: no such file"))
      << e;
  e = err("  pressure_field: {triangles: sheet, file: half.csv, tolerance: 0.2}\n");
  EXPECT_TRUE(has(e, "half.csv: the centroid") && has(e, "of triangle") &&
              has(e, "farther than the tolerance 0.2 m"))
      << e;
  e = err("  pressure_field: {triangles: sheet, file: half.dat}\n");
  EXPECT_TRUE(has(e, "effects.pressure_field.file") && has(e, "(.csv) or a legacy VTK surface (.vtk)")) << e;
  e = err("  pressure_field: {triangles: sheet, file: half.csv, quantity: cp}\n");
  EXPECT_TRUE(has(e, "dynamic_pressure")) << e;
  e = err("  pressure_field: {triangles: sheet, file: half.csv, dynamic_pressure: 3}\n");
  EXPECT_TRUE(has(e, "only with `quantity: cp`")) << e;
  e = err("  pressure_field: {triangles: sheet, file: half.csv, scale: .nan}\n");
  EXPECT_TRUE(has(e, "effects.pressure_field.scale")) << e;
  e = err("  pressure_field: {triangles: sheet, file: half.csv, projection: consistent}\n");
  EXPECT_TRUE(has(e, "effects.pressure_field.projection: only for a surface (.vtk)")) << e;
  e = err("  pressure_field: {triangles: sheet, file: half.vtk, projection: conservatve}\n");
  EXPECT_TRUE(has(e, "effects.pressure_field.projection") && has(e, "conservative")) << e;
  e = err("  pressure_field: {triangles: sheet, file: half.csv, folower: true}\n");
  EXPECT_TRUE(has(e, "did you mean 'follower'")) << e;
}

// ---------------------------------------------------------------- on the parafoil's closed skin

namespace {

InterfaceMesh parafoilSkin(int points, int divisions) {
  fsi::structure::parafoil::ParafoilParams q;
  q.section = fsi::structure::parafoil::AirfoilSection::naca("4415", "test");
  q.chordwisePoints = points;
  q.spanDivisions = divisions;
  const fsi::structure::MeshData m = fsi::structure::parafoil::buildParafoil(q, "wing");
  InterfaceMesh s;
  s.name = "skin";
  std::vector<int> local(m.points.size(), -1);
  for (int t : m.triangleGroups.at("skin")) {
    std::vector<int> f;
    for (int k = 0; k < 3; ++k) {
      const int g = m.triangles[std::size_t(t)][std::size_t(k)];
      if (local[std::size_t(g)] < 0) {
        local[std::size_t(g)] = s.numPoints();
        s.points.push_back(
            {m.points[std::size_t(g)][0], m.points[std::size_t(g)][1], m.points[std::size_t(g)][2]});
      }
      f.push_back(local[std::size_t(g)]);
    }
    s.addFace(f);
  }
  return s;
}

double volumeOf(const InterfaceMesh& m) {
  double v = 0;
  for (int f = 0; f < m.numFaces(); ++f) {
    const auto &a = m.points[std::size_t(m.face(f)[0])], &b = m.points[std::size_t(m.face(f)[1])],
               &c = m.points[std::size_t(m.face(f)[2])];
    v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
          a[2] * (b[0] * c[1] - b[1] * c[0])) /
         6.0;
  }
  return v;
}

}  // namespace

TEST(PressureField, ParafoilSkinFromAFinerSkinOfTheSameWing) {
  // A closed outer surface under a linear p: the resultant −∮ p n dA = −V ∇p (Gauss), small next to ∮ |p| dA
  // (here 9 N against 405 N). The file is the same wing generated finer (the "CFD" surface); default
  // tolerance. The conservative projection keeps ∮ p dA to round-off but hands the file's larger area (it
  // follows the curved section more closely) to the triangles as pressure, which a closed surface does not
  // cancel: its resultant error is second order but large here. The consistent one reproduces a linear p
  // exactly (the projection's gap correction, docs/PROJECTION.md), so its resultant is exact.
  const InterfaceMesh fine = parafoilSkin(48, 6);
  SurfaceField source{fine, {}};
  for (const auto& x : fine.points) source.values.push_back(linearP(x));
  double previous[2] = {1e300, 1e300};
  for (auto [points, divisions] : {std::pair{12, 1}, std::pair{24, 2}}) {
    const InterfaceMesh skin = parafoilSkin(points, divisions);
    const double v = volumeOf(skin);
    const std::array<double, 3> gauss{-v * kB, 0.0, -v * kC};
    for (int variant = 0; variant < 2; ++variant) {
      const std::vector<double> p =
          (variant == 0 ? conservativeTrianglePressure : consistentTrianglePressure)(
              skin, source, skin.meanEdgeLength(), nodeName);
      if (variant == 0) {
        EXPECT_NEAR(sumPA(skin, p), surfaceIntegral(source), 1e-12 * std::abs(surfaceIntegral(source)))
            << points;
      }
      std::vector<double> along(p.size());
      for (std::size_t e = 0; e < p.size(); ++e) along[e] = -p[e];
      const double err = relError(resultantOf(skin, along, false).force, gauss);
      if (variant == 0) {
        EXPECT_LT(err, previous[variant] / 3) << variant << " " << points;  // second order
      } else {
        // The projection's gap correction carries a linear p across the gap between the two skins exactly.
        EXPECT_LT(err, 1e-12) << points;
      }
      previous[variant] = err;
    }
  }
}

TEST(PressureField, ConsistentProjectionTakesAFileLargerThanTheSet) {
  // The file covers twice the panel's length: the consistent projection samples only where the triangles
  // are (the analytic resultant of the panel), the conservative one refuses (the rest of the file's force
  // would have nowhere to go).
  const InterfaceMesh skin = panel(12, 12, false);
  InterfaceMesh longer = panel(40, 30, true, 0.3);
  for (auto& x : longer.points) x[0] = 2.0 * x[0] - 0.5;  // x in [−0.5, 1.5]
  const SurfaceField source = sampled(longer);
  EXPECT_THROW(conservativeTrianglePressure(skin, source, 0.05, nodeName), InputError);
  const std::vector<double> p = consistentTrianglePressure(skin, source, 0.05, nodeName);
  std::vector<double> along(p.size());
  for (std::size_t e = 0; e < p.size(); ++e) along[e] = -p[e];
  const Resultant r = resultantOf(skin, along, true);
  EXPECT_LT(relError(r.force, analytic().force), 1e-3);
  EXPECT_LT(relError(r.moment, analytic().moment), 1e-3);
  // A file that misses part of the panel: the first point without data is named with its node.
  InterfaceMesh shorter = panel(20, 20, true);
  for (auto& x : shorter.points) x[0] *= 0.5;
  try {
    consistentTrianglePressure(skin, sampled(shorter), 0.05, nodeName);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_TRUE(has(e.what(), "farther than the tolerance 0.05 m from the file's surface") &&
                has(e.what(), "node "))
        << e.what();
  }
}
