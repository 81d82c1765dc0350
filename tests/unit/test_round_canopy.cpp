// The round_canopy generator's constructed shape against closed forms: cloth areas of the flat and conical
// canopies (planar gores: exact at any resolution), the hemispherical canopy's area by an independent
// quadrature and the mesh's second-order convergence to it, the continuum limits of D_c/D0, the line
// geometry, rotational and mirror symmetry, the sets, outward normals and located errors.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "TestScenes.hpp"
#include "structure/model/Error.hpp"
#include "structure/roundcanopy/RoundCanopyGeometry.hpp"
#include "structure/scene/Scene.hpp"

namespace fsi::structure::roundcanopy {
namespace {

constexpr double kPi = 3.14159265358979323846;
using Vec3 = std::array<double, 3>;

Vec3 sub(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const Vec3& a) {
  return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

Vec3 normal(const MeshData& m, int t) {
  const auto& tri = m.triangles[t];
  return cross(sub(m.points[tri[1]], m.points[tri[0]]), sub(m.points[tri[2]], m.points[tri[0]]));
}

double meshArea(const MeshData& m) {
  double a = 0;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) a += 0.5 * norm(normal(m, int(t)));
  return a;
}

RoundCanopyParams params(CanopyShape shape, int gores = 12, double vent = 0.0) {
  RoundCanopyParams p;
  p.shape = shape;
  p.nominalDiameter = 2.0;
  p.gores = gores;
  p.ventDiameter = vent;
  p.coneAngleDeg = 25.0;
  return p;
}

TEST(RoundCanopy, FlatCanopyIsTheRegularPolygonOfAreaS0) {
  for (int n : {3, 8, 28}) {
    RoundCanopyParams p = params(CanopyShape::flat, n, 0.3);
    const double s0 = kPi;  // D0 = 2
    // A flat canopy of N flat gores is a regular N-gon of circumradius R: S0 = (N/2) sin(2π/N) R².
    const double r = std::sqrt(s0 / (0.5 * n * std::sin(2 * kPi / n)));
    const RoundCanopyDesign d = designRoundCanopy(p);
    EXPECT_NEAR(d.skirtRadius, r, 1e-10 * r) << n << " gores";
    EXPECT_NEAR(d.constructedDiameter, 2 * r, 1e-10);
    EXPECT_NEAR(d.ventArea, 0.5 * n * std::sin(2 * kPi / n) * 0.15 * 0.15, 1e-10) << "vent polygon";
    EXPECT_DOUBLE_EQ(d.height, 0.0);
    for (int radial : {1, 5}) {
      p.radialDivisions = radial;
      const MeshData m = buildRoundCanopy(p);
      // The open vent is not cloth of the mesh.
      EXPECT_NEAR(meshArea(m), s0 - d.ventArea, 1e-10) << n << " gores, " << radial << " divisions";
      for (std::size_t t = 0; t < m.triangles.size(); ++t) ASSERT_GT(normal(m, int(t))[2], 0) << "normal up";
    }
  }
}

TEST(RoundCanopy, ConicalCanopyIsTheRegularPyramidOfAreaS0) {
  const int n = 16;
  RoundCanopyParams p = params(CanopyShape::conical, n);
  const double a = 25.0 * kPi / 180;
  // Lateral area of a regular N-gonal pyramid of base circumradius R, height R tan α:
  // N · R sin(π/N) · √((R cos(π/N))² + (R tan α)²) = S0.
  const double unit = n * std::sin(kPi / n) * std::hypot(std::cos(kPi / n), std::tan(a));
  const double r = std::sqrt(kPi / unit);
  const RoundCanopyDesign d = designRoundCanopy(p);
  EXPECT_NEAR(d.skirtRadius, r, 1e-9 * r);
  EXPECT_NEAR(d.height, r * std::tan(a), 1e-9);
  const MeshData m = buildRoundCanopy(p);
  EXPECT_NEAR(meshArea(m), kPi, 1e-9) << "planar gores: the mesh is exact";
  // Outward normals: away from the axis and up.
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const Vec3 nv = normal(m, int(t));
    const auto& tri = m.triangles[t];
    Vec3 c{};
    for (int k : tri)
      for (int i = 0; i < 3; ++i) c[i] += m.points[k][i] / 3;
    ASSERT_GT(nv[2], 0);
    ASSERT_GT(nv[0] * c[0] + nv[1] * c[1], 0);
  }
}

TEST(RoundCanopy, HemisphericalAreaByAnIndependentQuadratureAndSecondOrderMesh) {
  const int n = 10;
  RoundCanopyParams p = params(CanopyShape::hemispherical, n);
  // Flat gores between quarter-circle radials: area of one gore = ∫ w(u) |M'(u)| du with the chord
  // w = 2 sin(πu/2) sin(π/N) and the gore's centre line M = (sin(πu/2) cos(π/N), cos(πu/2)); Simpson's rule.
  const int steps = 20000;
  double unit = 0;
  for (int i = 0; i <= steps; ++i) {
    const double u = double(i) / steps, c = (i == 0 || i == steps) ? 1 : (i % 2 ? 4 : 2);
    const double w = 2 * std::sin(kPi * u / 2) * std::sin(kPi / n);
    const double dm = kPi / 2 * std::hypot(std::cos(kPi * u / 2) * std::cos(kPi / n), std::sin(kPi * u / 2));
    unit += c * w * dm / (3.0 * steps);
  }
  unit *= n;
  EXPECT_NEAR(clothArea(p, 0, 1), unit, 1e-9 * unit);
  const double r = std::sqrt(kPi / unit);
  EXPECT_NEAR(designRoundCanopy(p).skirtRadius, r, 1e-8);
  // The mesh converges to S0 = π at second order along the radials.
  std::vector<double> err;
  for (int radial : {6, 12, 24}) {
    p.radialDivisions = radial;
    err.push_back(kPi - meshArea(buildRoundCanopy(p)));
  }
  EXPECT_GT(err[0], 0) << "chords cut the curve short";
  for (int i = 0; i + 1 < int(err.size()); ++i) {
    const double rate = std::log2(err[i] / err[i + 1]);
    EXPECT_NEAR(rate, 2.0, 0.1) << "refinement " << i;
  }
}

TEST(RoundCanopy, BulgedGoresConvergeAtSecondOrderAndShrinkTheConstructedDiameter) {
  RoundCanopyParams p = params(CanopyShape::flat, 8, 0.2);
  const double flatDc = designRoundCanopy(p).constructedDiameter;
  p.bulge = 0.15;
  const RoundCanopyDesign d = designRoundCanopy(p);
  EXPECT_LT(d.constructedDiameter, flatDc) << "more cloth per gore: a smaller canopy for the same S0";
  std::vector<double> err;
  for (int k : {1, 2, 4}) {
    p.radialDivisions = 4 * k;
    p.goreDivisions = 4 * k;
    err.push_back(kPi - d.ventArea - meshArea(buildRoundCanopy(p)));
  }
  for (int i = 0; i + 1 < int(err.size()); ++i) EXPECT_NEAR(std::log2(err[i] / err[i + 1]), 2.0, 0.15);
  // The cross-section of a flat canopy's gore is the circular arc through the radials with sagitta 0.15 w:
  // at the quarter chord its height is √(ρ² − (w/4)²) − (ρ − h), ρ = (w²/4 + h²)/(2h).
  p.radialDivisions = 3;
  p.goreDivisions = 4;
  const MeshData m = buildRoundCanopy(p);
  const std::vector<int>& skirt = m.nodeGroups.at("skirt");
  const double w = 2 * d.skirtRadius * std::sin(kPi / 8), h = 0.15 * w, rho = (w * w / 4 + h * h) / (2 * h);
  for (int k = 0; k < 8; ++k) {
    EXPECT_NEAR(m.points[skirt[4 * k]][2], 0.0, 1e-12) << "radial";
    EXPECT_NEAR(m.points[skirt[4 * k + 1]][2], std::sqrt(rho * rho - w * w / 16) - (rho - h), 1e-12);
    EXPECT_NEAR(m.points[skirt[4 * k + 2]][2], h, 1e-12) << "mid-gore";
  }
}

TEST(RoundCanopy, ContinuumLimitsOfTheConstructedDiameter) {
  // Many gores: the cone's area π R²/cos α gives D_c/D0 = √(cos α); the hemisphere's 2π R² gives 1/√2.
  RoundCanopyParams cone = params(CanopyShape::conical, 400);
  EXPECT_NEAR(designRoundCanopy(cone).constructedDiameter / 2.0, std::sqrt(std::cos(25 * kPi / 180)), 1e-4);
  RoundCanopyParams hemi = params(CanopyShape::hemispherical, 400);
  EXPECT_NEAR(designRoundCanopy(hemi).constructedDiameter / 2.0, 1 / std::sqrt(2.0), 1e-4);
}

TEST(RoundCanopy, LinesMeetAtTheConfluenceWithTheirLength) {
  RoundCanopyParams p = params(CanopyShape::conical, 12, 0.2);
  p.lineLength = 1.1;
  p.lineElements = 5;
  p.riserLength = 0.4;
  const MeshData m = buildRoundCanopy(p);
  const RoundCanopyDesign d = designRoundCanopy(p);
  const int conf = m.nodeGroups.at("confluence").at(0), pay = m.nodeGroups.at("payload").at(0);
  const double depth = std::sqrt(2.2 * 2.2 - d.skirtRadius * d.skirtRadius);
  EXPECT_NEAR(m.points[conf][2], -depth, 1e-12);
  EXPECT_NEAR(m.points[pay][2], -depth - 0.4, 1e-12);
  ASSERT_EQ(m.lineGroups.at("lines").size(), 12u * 5);
  ASSERT_EQ(m.lineGroups.at("riser").size(), 5u);
  double total = 0;
  for (int e : m.lineGroups.at("lines")) total += norm(sub(m.points[m.lines[e][1]], m.points[m.lines[e][0]]));
  EXPECT_NEAR(total, 12 * 2.2, 1e-10) << "every line l_s = 1.1 D0";
  // Each line starts at a radial's skirt end.
  std::set<int> ends(m.nodeGroups.at("radial_ends").begin(), m.nodeGroups.at("radial_ends").end());
  int starts = 0;
  for (int e : m.lineGroups.at("lines")) starts += ends.count(m.lines[e][0]);
  EXPECT_EQ(starts, 12);
  for (int k : ends) EXPECT_NEAR(std::hypot(m.points[k][0], m.points[k][1]), d.skirtRadius, 1e-12);
}

TEST(RoundCanopy, SetsPartitionTheCanopyAndTapesFollowTheSeams) {
  RoundCanopyParams p = params(CanopyShape::hemispherical, 9, 0.3);
  p.radialDivisions = 7;
  p.goreDivisions = 3;
  const MeshData m = buildRoundCanopy(p);
  EXPECT_EQ(m.triangles.size(), 9u * 3 * 7 * 2);
  std::vector<int> seen(m.triangles.size(), 0);
  for (int k = 1; k <= 9; ++k)
    for (int t : m.triangleGroups.at("gore_" + std::to_string(k))) ++seen[t];
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int c) { return c == 1; }));
  EXPECT_EQ(m.lineGroups.at("radials").size(), 9u * 7);
  EXPECT_EQ(m.lineGroups.at("skirt_band").size(), 9u * 3);
  EXPECT_EQ(m.lineGroups.at("vent_band").size(), 9u * 3);
  EXPECT_EQ(m.lineGroups.at("tapes").size(), 9u * (7 + 3 + 3));
  EXPECT_EQ(m.nodeGroups.at("skirt").size(), 27u);
  for (int k : m.nodeGroups.at("skirt")) EXPECT_NEAR(m.points[k][2], 0.0, 1e-12);
  // The vent edge: radius 0.15 at the radials, inside it on the straight chords between them.
  double ventMax = 0;
  for (int k : m.nodeGroups.at("vent"))
    ventMax = std::max(ventMax, std::hypot(m.points[k][0], m.points[k][1]));
  EXPECT_NEAR(ventMax, 0.15, 1e-9);
  // Without a vent: one apex node, a fan of triangles around it, no vent band.
  p.ventDiameter = 0;
  const MeshData closed = buildRoundCanopy(p);
  EXPECT_EQ(closed.nodeGroups.at("apex").size(), 1u);
  EXPECT_EQ(closed.triangles.size(), 9u * 3 * (7 * 2 - 1));
  EXPECT_TRUE(closed.lineGroups.at("vent_band").empty());
  EXPECT_NEAR(meshArea(closed) + 0.0, kPi, 0.05 * kPi);
}

/// Maps every point to the index of the point at its image under `f` (or -1).
template <class F>
std::vector<int> imageOf(const MeshData& m, F f) {
  std::map<std::array<long, 3>, int> at;
  auto key = [](const Vec3& x) {
    return std::array<long, 3>{std::lround(x[0] * 1e8), std::lround(x[1] * 1e8), std::lround(x[2] * 1e8)};
  };
  for (std::size_t i = 0; i < m.points.size(); ++i) at[key(m.points[i])] = int(i);
  std::vector<int> img(m.points.size(), -1);
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const auto it = at.find(key(f(m.points[i])));
    img[i] = it == at.end() ? -1 : it->second;
  }
  return img;
}

std::set<std::array<int, 3>> triangleSet(const MeshData& m, const std::vector<int>& img, bool flip) {
  std::set<std::array<int, 3>> s;
  for (const auto& t : m.triangles) {
    std::array<int, 3> a{img[t[0]], img[t[1]], img[t[2]]};
    if (flip) std::swap(a[1], a[2]);
    std::rotate(a.begin(), std::min_element(a.begin(), a.end()), a.end());
    s.insert(a);
  }
  return s;
}

TEST(RoundCanopy, RotationalAndMirrorSymmetry) {
  RoundCanopyParams p = params(CanopyShape::conical, 7, 0.25);
  p.goreDivisions = 4;
  p.bulge = 0.1;
  p.radialDivisions = 5;
  const MeshData m = buildRoundCanopy(p);
  const std::vector<int> id = imageOf(m, [](const Vec3& x) { return x; });
  const auto original = triangleSet(m, id, false);
  // Rotation by one gore.
  const double a = 2 * kPi / 7;
  const auto rot = imageOf(m, [&](const Vec3& x) {
    return Vec3{std::cos(a) * x[0] - std::sin(a) * x[1], std::sin(a) * x[0] + std::cos(a) * x[1], x[2]};
  });
  ASSERT_TRUE(std::none_of(rot.begin(), rot.end(), [](int i) { return i < 0; }));
  EXPECT_EQ(triangleSet(m, rot, false), original);
  // Mirror about the first gore's centre plane (azimuth π/N): nodes and triangles (orientation reversed).
  const double c = std::cos(2 * kPi / 7), s = std::sin(2 * kPi / 7);
  const auto mir = imageOf(m, [&](const Vec3& x) {
    return Vec3{c * x[0] + s * x[1], s * x[0] - c * x[1], x[2]};
  });
  ASSERT_TRUE(std::none_of(mir.begin(), mir.end(), [](int i) { return i < 0; }));
  EXPECT_EQ(triangleSet(m, mir, true), original);
}

TEST(RoundCanopy, ImpossibleDesignsNameTheParameter) {
  auto fails = [](RoundCanopyParams p, const std::string& key) {
    try {
      designRoundCanopy(p);
      ADD_FAILURE() << key << ": no error";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("parameter '" + key + "'"), std::string::npos) << e.what();
    }
  };
  RoundCanopyParams p = params(CanopyShape::conical);
  auto q = p;
  q.gores = 2;
  fails(q, "gores");
  q = p;
  q.nominalDiameter = -1;
  fails(q, "nominal_diameter");
  q = p;
  q.coneAngleDeg = 0;
  fails(q, "cone_angle");
  q = p;
  q.ventDiameter = 1.5;
  fails(q, "vent_diameter");
  q = p;
  q.lineLength = 0.4;
  fails(q, "line_length");
  q = p;
  q.ventDiameter = std::nan("");
  fails(q, "vent_diameter");
  q = p;
  q.riserLength = 0.0;
  fails(q, "riser_length");
  q = p;
  q.bulge = 0.8;
  fails(q, "bulge");
  q = p;
  q.gores = 1000;
  q.goreDivisions = 100;
  q.radialDivisions = 100;
  fails(q, "radial_divisions");
  q = p;
  q.lineStretch = 1.5;
  fails(q, "line_stretch");
}

// The start at line stretch against what it must be: every cloth node s times as far from the axis at its
// azimuth; no cloth edge and no tape longer than constructed (a stress-free start), and along every ring step
// some meridian segment exactly its constructed length (drawn out as far as the cloth allows); the lines
// straight from the confluence point, which stays, with their length l_s; the constructed shape unchanged.
TEST(RoundCanopy, LineStretchStartIsSlenderStressFreeAndTaut) {
  for (CanopyShape shape : {CanopyShape::flat, CanopyShape::conical, CanopyShape::hemispherical}) {
    RoundCanopyParams p = params(shape, 10, 0.2);
    p.goreDivisions = 3;
    p.bulge = shape == CanopyShape::flat ? 0.1 : 0.0;
    p.riserLength = 0.5;
    const double s = 0.15;
    p.lineStretch = s;
    const MeshData m = buildRoundCanopy(p);
    RoundCanopyParams built = p;
    built.lineStretch.reset();
    const MeshData ref = buildRoundCanopy(built);
    ASSERT_EQ(m.startPoints.size(), m.points.size());
    EXPECT_TRUE(ref.startPoints.empty());
    for (std::size_t i = 0; i < m.points.size(); ++i)
      for (int k = 0; k < 3; ++k)
        ASSERT_EQ(m.points[i][k], ref.points[i][k]) << "the reference is the cut shape";
    const auto& X = m.points;
    const auto& x = m.startPoints;
    std::set<int> cloth;
    for (const auto& t : m.triangles) cloth.insert(t.begin(), t.end());
    for (int i : cloth) {
      EXPECT_NEAR(x[i][0], s * X[i][0], 1e-12);
      EXPECT_NEAR(x[i][1], s * X[i][1], 1e-12);
    }
    double longest = 0;
    int atLength = 0;
    for (const auto& t : m.triangles)
      for (int e = 0; e < 3; ++e) {
        const int a = t[e], b = t[(e + 1) % 3];
        const double ratio = norm(sub(x[b], x[a])) / norm(sub(X[b], X[a]));
        longest = std::max(longest, ratio);
        atLength += ratio > 1 - 1e-12;
      }
    EXPECT_LE(longest, 1 + 1e-12) << "no cloth edge stretched";
    EXPECT_GE(atLength, p.radialDivisions) << "one segment at its length per ring step at least";
    for (int e : m.lineGroups.at("tapes"))
      EXPECT_LE(norm(sub(x[m.lines[e][1]], x[m.lines[e][0]])),
                norm(sub(X[m.lines[e][1]], X[m.lines[e][0]])) + 1e-12);
    const int conf = m.nodeGroups.at("confluence").at(0), pay = m.nodeGroups.at("payload").at(0);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(x[conf][k], X[conf][k]);
      EXPECT_EQ(x[pay][k], X[pay][k]);
    }
    double total = 0;
    for (int e : m.lineGroups.at("lines")) {
      const Vec3 d = sub(x[m.lines[e][1]], x[m.lines[e][0]]);
      total += norm(d);
      // Straight: every segment of a line along the same direction as the skirt end to the confluence.
      const int end = m.lines[e - e % p.lineElements][0];
      const Vec3 whole = sub(x[conf], x[end]);
      EXPECT_NEAR(norm(cross(d, whole)), 0.0, 1e-10);
    }
    EXPECT_NEAR(total, 10 * p.lineLength * p.nominalDiameter, 1e-10) << "lines taut at l_s";
  }
}

}  // namespace
}  // namespace fsi::structure::roundcanopy

namespace fsi::structure::roundcanopy {
namespace {

constexpr const char* kScene = R"(materials:
  cloth: {type: membrane, young: 5.0e8, poisson: 0.3, thickness: 1.0e-4, density: 1100}
  tape: {type: cable, young: 2.0e9, area: 2.0e-6, density: 1100}
meshes:
  canopy:
    generator: {type: round_canopy, shape: conical, nominal_diameter: 2.0, gores: 12, vent_diameter: 0.2, cone_angle: 25, riser_length: 0.5}
    material: cloth
    cable_material: tape
constraints:
  - {nodes: canopy/payload, fix: all}
time: {end: 0.001}
)";

std::string sceneError(const std::string& from, const std::string& to) {
  return fsi::test::sceneError(fsi::test::replaced(kScene, from, to), "round.yaml");
}

TEST(RoundCanopyScene, TheGeneratorBuildsTheCanopyOfAScene) {
  const auto scene = fsi::structure::loadSceneFromString(kScene, "round.yaml");
  const auto& m = scene.model->meshes.at(0).source;
  EXPECT_EQ(m.triangles.size(), 12u * 2 * 12 * 2);
  EXPECT_EQ(m.nodeGroups.at("payload").size(), 1u);
  EXPECT_EQ(scene.model->membranes.count, 576);
}

TEST(RoundCanopyScene, ARunStartsAtLineStretchWithTheCutShapeAsReference) {
  const auto scene = fsi::structure::loadSceneFromString(
      fsi::test::replaced(kScene, "riser_length: 0.5}", "riser_length: 0.5, line_stretch: 0.2}"),
      "round.yaml");
  const Model& model = *scene.model;
  const MeshData& m = model.meshes.at(0).source;
  ASSERT_EQ(m.startPoints.size(), m.points.size());
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const int n = model.meshes.at(0).node[i];
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(model.nodes.X[3 * n + k], m.points[i][k]) << "the reference: the constructed shape";
      EXPECT_EQ(model.nodes.x[3 * n + k], m.startPoints[i][k]) << "the start: line stretch";
    }
  }
}

// canopy_pressure's apparent_mass h: ρ h per cloth area of inertia on the cloth's nodes, no weight.
TEST(RoundCanopyScene, ApparentMassAddsInertiaNotWeight) {
  const std::string pressure =
      "effects:\n  canopy_pressure: {triangles: canopy/canopy, mouth: canopy/skirt, wind: [0, 0, 10]";
  const auto plain = fsi::structure::loadSceneFromString(
      fsi::test::replaced(kScene, "time:", pressure + "}\ntime:"), "round.yaml");
  const auto added = fsi::structure::loadSceneFromString(
      fsi::test::replaced(kScene, "time:", pressure + ", apparent_mass: 0.3, density: 1.2}\ntime:"),
      "round.yaml");
  double m0 = 0, m1 = 0, w0 = 0, w1 = 0;
  for (double v : plain.model->nodes.mass) m0 += v;
  for (double v : added.model->nodes.mass) m1 += v;
  for (double v : plain.model->nodes.physicalMass) w0 += v;
  for (double v : added.model->nodes.physicalMass) w1 += v;
  EXPECT_NEAR(m1 - m0, 1.2 * 0.3 * meshArea(plain.model->meshes.at(0).source), 1e-9)
      << "ρ h S (the cut area)";
  EXPECT_EQ(w1, w0) << "the air weighs nothing in air";
  // A mouth of fewer than 3 nodes cannot have an area: an error at the key.
  EXPECT_NE(
      fsi::test::sceneError(fsi::test::replaced(kScene, "time:",
                                                "effects:\n  canopy_pressure: {triangles: canopy/canopy, "
                                                "mouth: canopy/confluence, wind: [0, 0, 10]}\ntime:"),
                            "round.yaml")
          .find("mouth"),
      std::string::npos);
}

TEST(RoundCanopyScene, ErrorsAreLocatedAtTheKey) {
  // Out of a key's range: at the key, from the schema.
  EXPECT_NE(sceneError("gores: 12", "gores: 2").find("round.yaml:6:"), std::string::npos);
  EXPECT_NE(sceneError("gores: 12", "gores: 2").find("gores"), std::string::npos);
  // A key that cannot take effect.
  EXPECT_NE(sceneError("shape: conical", "shape: flat").find("cone_angle"), std::string::npos);
  // Depending on other keys: the design's message at the entry.
  const std::string vent = sceneError("vent_diameter: 0.2", "vent_diameter: 1.9");
  EXPECT_NE(vent.find("round.yaml:6:"), std::string::npos) << vent;
  EXPECT_NE(vent.find("parameter 'vent_diameter'"), std::string::npos) << vent;
  // Misspelt key: did you mean.
  EXPECT_NE(sceneError("gores: 12", "gore: 12").find("gores"), std::string::npos);
  EXPECT_NE(sceneError("riser_length: 0.5}", "riser_length: 0.5, line_stretch: 0}").find("line_stretch"),
            std::string::npos);
}

}  // namespace
}  // namespace fsi::structure::roundcanopy
