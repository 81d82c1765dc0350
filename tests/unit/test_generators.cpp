// Built-in parametric meshes: counts, areas, orientation, groups, tags and parameter checks.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "structure/model/Error.hpp"
#include "structure/scene/Generators.hpp"

namespace fsi::structure {
namespace {

constexpr double kPi = 3.14159265358979323846;

Point3 sub(const Point3& a, const Point3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Point3& a, const Point3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
double norm(const Point3& a) {
  return std::sqrt(dot(a, a));
}

// Twice-area vector of triangle t (right-hand rule on its node order).
Point3 areaVector(const MeshData& m, int t) {
  const auto& tri = m.triangles[static_cast<std::size_t>(t)];
  return cross(sub(m.points[tri[1]], m.points[tri[0]]), sub(m.points[tri[2]], m.points[tri[0]]));
}

double totalArea(const MeshData& m) {
  double area = 0;
  for (int t = 0; t < static_cast<int>(m.triangles.size()); ++t) area += 0.5 * norm(areaVector(m, t));
  return area;
}

// Every triangle turns counter-clockwise about `normal`, with a clearly non-zero area.
void expectOriented(const MeshData& m, const std::vector<int>& triangles, const Point3& normal) {
  for (const int t : triangles) {
    const Point3 a = areaVector(m, t);
    EXPECT_GT(dot(a, normal), 1e-6 * norm(a) * norm(normal)) << m.name << " triangle " << t;
  }
}

std::vector<int> allTriangles(const MeshData& m) {
  std::vector<int> v(m.triangles.size());
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = static_cast<int>(i);
  return v;
}

// Tags 1..n, indices in range, no degenerate element.
void expectWellFormed(const MeshData& m, const std::string& name) {
  EXPECT_EQ(m.name, name);
  ASSERT_EQ(m.pointTags.size(), m.points.size());
  ASSERT_EQ(m.triangleTags.size(), m.triangles.size());
  ASSERT_EQ(m.lineTags.size(), m.lines.size());
  for (std::size_t i = 0; i < m.pointTags.size(); ++i) EXPECT_EQ(m.pointTags[i], static_cast<long>(i) + 1);
  for (std::size_t i = 0; i < m.triangleTags.size(); ++i)
    EXPECT_EQ(m.triangleTags[i], static_cast<long>(i) + 1);
  for (std::size_t i = 0; i < m.lineTags.size(); ++i) EXPECT_EQ(m.lineTags[i], static_cast<long>(i) + 1);
  const int n = static_cast<int>(m.points.size());
  for (const auto& t : m.triangles) {
    for (const int v : t) ASSERT_TRUE(v >= 0 && v < n);
    EXPECT_TRUE(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
  }
  for (const auto& l : m.lines) {
    for (const int v : l) ASSERT_TRUE(v >= 0 && v < n);
    EXPECT_NE(l[0], l[1]);
  }
  for (const auto& groups : {m.nodeGroups, m.triangleGroups, m.lineGroups}) {
    for (const auto& [groupName, members] : groups) {
      EXPECT_TRUE(std::is_sorted(members.begin(), members.end())) << groupName;
      EXPECT_TRUE(std::adjacent_find(members.begin(), members.end()) == members.end()) << groupName;
    }
  }
}

// Pairs of distinct nodes at the same position.
std::vector<std::pair<int, int>> coincidentPairs(const MeshData& m) {
  std::vector<int> order(m.points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return m.points[a] < m.points[b]; });
  std::vector<std::pair<int, int>> pairs;
  for (std::size_t k = 0; k + 1 < order.size(); ++k) {
    // Exact comparison is enough: generators compute shared positions with the same expression.
    if (norm(sub(m.points[order[k]], m.points[order[k + 1]])) < 1e-12) {
      pairs.emplace_back(std::min(order[k], order[k + 1]), std::max(order[k], order[k + 1]));
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

// Closed and consistently oriented: every directed edge once, its reverse once.
void expectClosedOrientedSurface(const MeshData& m) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << edge.first << "-" << edge.second;
    const auto reverse = directed.find({edge.second, edge.first});
    EXPECT_TRUE(reverse != directed.end() && reverse->second == 1) << edge.first << "-" << edge.second;
  }
}

bool hasEdge(const MeshData& m, int a, int b) {
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      const int p = t[k], q = t[(k + 1) % 3];
      if ((p == a && q == b) || (p == b && q == a)) return true;
    }
  }
  return false;
}

void expectInputError(const std::function<void()>& call, const std::vector<std::string>& words) {
  try {
    call();
    ADD_FAILURE() << "no InputError thrown";
  } catch (const InputError& e) {
    const std::string message = e.what();
    for (const auto& w : words) EXPECT_NE(message.find(w), std::string::npos) << message << " lacks " << w;
  }
}

// ---------------------------------------------------------------------------------------------------------

TEST(GeneratorRectangle, CountsAreaOrientationGroups) {
  for (const std::string pattern : {"ruled", "alternating", "cross"}) {
    SCOPED_TRACE(pattern);
    RectangleParams p;
    p.size = {2.0, 1.5};
    p.divisions = {4, 3};
    p.center = {1.0, 2.0, 3.0};
    p.pattern = pattern;
    const MeshData m = rectangle(p, "sheet");
    expectWellFormed(m, "sheet");
    const bool cross = pattern == "cross";
    EXPECT_EQ(m.points.size(), cross ? 20u + 12u : 20u);
    EXPECT_EQ(m.triangles.size(), cross ? 48u : 24u);
    EXPECT_NEAR(totalArea(m), 3.0, 1e-12);
    expectOriented(m, allTriangles(m), {0, 0, 1});
    EXPECT_TRUE(coincidentPairs(m).empty());
    for (const auto& q : m.points) EXPECT_EQ(q[2], 3.0);

    EXPECT_EQ(m.nodeGroups.at("boundary").size(), 14u);
    for (const auto& [group, coordinate, value] :
         {std::tuple{"xmin", 0, 0.0}, {"xmax", 0, 2.0}, {"ymin", 1, 1.25}, {"ymax", 1, 2.75}}) {
      const auto& nodes = m.nodeGroups.at(group);
      EXPECT_EQ(nodes.size(), coordinate == 0 ? 4u : 5u) << group;
      for (const int v : nodes) EXPECT_EQ(m.points[v][coordinate], value) << group;
    }
    for (const int v : m.nodeGroups.at("boundary")) {
      const auto& q = m.points[v];
      EXPECT_TRUE(q[0] == 0.0 || q[0] == 2.0 || q[1] == 1.25 || q[1] == 2.75);
    }
    EXPECT_EQ(m.triangleGroups.at("all").size(), m.triangles.size());
  }
}

TEST(GeneratorRectangle, DiagonalPatterns) {
  RectangleParams p;
  p.divisions = {2, 2};
  const auto grid = [](int i, int j) { return j * 3 + i; };
  p.pattern = "ruled";
  const MeshData ruled = rectangle(p);
  EXPECT_TRUE(hasEdge(ruled, grid(0, 0), grid(1, 1)));
  EXPECT_TRUE(hasEdge(ruled, grid(1, 0), grid(2, 1)));
  EXPECT_FALSE(hasEdge(ruled, grid(2, 0), grid(1, 1)));
  p.pattern = "alternating";
  const MeshData alternating = rectangle(p);
  EXPECT_TRUE(hasEdge(alternating, grid(0, 0), grid(1, 1)));
  EXPECT_TRUE(hasEdge(alternating, grid(2, 0), grid(1, 1)));
  EXPECT_TRUE(hasEdge(alternating, grid(0, 2), grid(1, 1)));
  EXPECT_TRUE(hasEdge(alternating, grid(1, 1), grid(2, 2)));
  p.pattern = "cross";
  const MeshData crossed = rectangle(p);
  // Every centre node sits in the middle of its square and is used by exactly four triangles.
  for (int c = 9; c < 13; ++c) {
    int uses = 0;
    for (const auto& t : crossed.triangles) uses += static_cast<int>(std::count(t.begin(), t.end(), c));
    EXPECT_EQ(uses, 4);
  }
  EXPECT_DOUBLE_EQ(crossed.points[9][0], -0.25);
  EXPECT_DOUBLE_EQ(crossed.points[9][1], -0.25);
}

TEST(GeneratorDisc, CountsAreaOrientationGroups) {
  const double radius = 0.7;
  for (int n = 1; n <= 6; ++n) {
    SCOPED_TRACE(n);
    DiscParams p;
    p.radius = radius;
    p.rings = n;
    p.center = {0.5, -1.0, 2.0};
    const MeshData m = disc(p);
    expectWellFormed(m, "disc");
    EXPECT_EQ(m.points.size(), static_cast<std::size_t>(1 + 3 * n * (n + 1)));
    EXPECT_EQ(m.triangles.size(), static_cast<std::size_t>(6 * n * n));
    // The triangles tile the inscribed regular 6n-gon exactly.
    const double polygon = 0.5 * 6 * n * radius * radius * std::sin(2 * kPi / (6 * n));
    EXPECT_NEAR(totalArea(m), polygon, 1e-12);
    expectOriented(m, allTriangles(m), {0, 0, 1});
    EXPECT_TRUE(coincidentPairs(m).empty());
    EXPECT_EQ(m.nodeGroups.at("center"), std::vector<int>{0});
    EXPECT_EQ(m.points[0], p.center);
    const auto& rim = m.nodeGroups.at("rim");
    EXPECT_EQ(rim.size(), static_cast<std::size_t>(6 * n));
    for (const int v : rim) EXPECT_NEAR(norm(sub(m.points[v], p.center)), radius, 1e-14);
    EXPECT_EQ(m.triangleGroups.at("all").size(), m.triangles.size());
  }
}

TEST(GeneratorDisc, WellShapedAndConvergesToCircle) {
  DiscParams p;
  p.rings = 12;
  const MeshData m = disc(p);
  double minAngle = kPi;
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      const Point3 u = sub(m.points[t[(k + 1) % 3]], m.points[t[k]]);
      const Point3 w = sub(m.points[t[(k + 2) % 3]], m.points[t[k]]);
      minAngle = std::min(minAngle, std::acos(dot(u, w) / (norm(u) * norm(w))));
    }
  }
  EXPECT_GT(minAngle * 180 / kPi, 40.0);
  EXPECT_NEAR(totalArea(m), kPi, 0.01);
}

TEST(GeneratorSphereOctant, CountsOrientationGroups) {
  const double r = 1.3;
  const int n = 8;
  const MeshData m = sphereOctant({r, n}, "octant");
  expectWellFormed(m, "octant");
  EXPECT_EQ(m.points.size(), static_cast<std::size_t>((n + 1) * (n + 2) / 2));
  EXPECT_EQ(m.triangles.size(), static_cast<std::size_t>(n * n));
  EXPECT_TRUE(coincidentPairs(m).empty());
  for (const auto& q : m.points) {
    EXPECT_NEAR(norm(q), r, 1e-12);
    for (const double c : q) EXPECT_GE(c, 0.0);
  }
  for (int t = 0; t < static_cast<int>(m.triangles.size()); ++t) {
    const auto& tri = m.triangles[t];
    Point3 centroid{};
    for (const int v : tri)
      for (int c = 0; c < 3; ++c) centroid[c] += m.points[v][c] / 3;
    EXPECT_GT(dot(areaVector(m, t), centroid), 0.0) << t;
  }
  int axis = 0;
  for (const char* group : {"x0", "y0", "z0"}) {
    const auto& nodes = m.nodeGroups.at(group);
    EXPECT_EQ(nodes.size(), static_cast<std::size_t>(n + 1)) << group;
    for (const int v : nodes) EXPECT_EQ(m.points[v][axis], 0.0) << group;
    // No other node lies on that plane.
    int onPlane = 0;
    for (const auto& q : m.points) onPlane += q[axis] == 0.0 ? 1 : 0;
    EXPECT_EQ(onPlane, n + 1) << group;
    ++axis;
  }
  EXPECT_EQ(m.triangleGroups.at("all").size(), m.triangles.size());
}

TEST(GeneratorSphereOctant, AreaConvergesSecondOrder) {
  const double r = 2.0;
  const double exact = kPi * r * r / 2;
  double previous = 0;
  for (int n = 4; n <= 64; n *= 2) {
    const double error = exact - totalArea(sphereOctant({r, n}));
    EXPECT_GT(error, 0.0) << n;  // flat facets under the sphere
    if (previous > 0) {
      EXPECT_NEAR(previous / error, 4.0, 0.5) << n;
    }
    previous = error;
  }
  EXPECT_LT(previous / exact, 1e-3);
}

TEST(GeneratorCableChain, UniformAndPerSegmentDivisions) {
  CableChainParams p;
  p.points = {{0, 0, 0}, {1, 0, 0}, {1, 2, 0}};
  p.divisions = {2};
  MeshData m = cableChain(p, "cable");
  expectWellFormed(m, "cable");
  EXPECT_EQ(m.points.size(), 5u);
  EXPECT_EQ(m.lines.size(), 4u);
  EXPECT_EQ(m.points[2], (Point3{1, 0, 0}));
  EXPECT_EQ(m.points[3], (Point3{1, 1, 0}));

  p.divisions = {1, 4};
  m = cableChain(p, "cable");
  expectWellFormed(m, "cable");
  EXPECT_EQ(m.points.size(), 6u);
  ASSERT_EQ(m.lines.size(), 5u);
  double length = 0;
  for (std::size_t k = 0; k < m.lines.size(); ++k) {
    EXPECT_EQ(m.lines[k], (std::array<int, 2>{static_cast<int>(k), static_cast<int>(k) + 1}));
    length += norm(sub(m.points[m.lines[k][1]], m.points[m.lines[k][0]]));
  }
  EXPECT_NEAR(length, 3.0, 1e-14);
  EXPECT_NEAR(norm(sub(m.points[2], m.points[1])), 0.5, 1e-14);
  EXPECT_TRUE(coincidentPairs(m).empty());
  EXPECT_EQ(m.nodeGroups.at("start"), std::vector<int>{0});
  EXPECT_EQ(m.nodeGroups.at("end"), std::vector<int>{5});
  EXPECT_EQ(m.points[5], (Point3{1, 2, 0}));
  EXPECT_EQ(m.lineGroups.at("all").size(), 5u);
  EXPECT_TRUE(m.triangles.empty());
}

TEST(GeneratorStrip, CatenaryVStrip) {
  for (const std::string pattern : {"ruled", "alternating"}) {
    SCOPED_TRACE(pattern);
    StripParams p;
    p.path = {{-1, 0, 0}, {0, 0, -0.5}, {1, 0, 0}};
    p.divisions = {4};
    p.width = {0, 0.5, 0};
    p.across = 3;
    p.pattern = pattern;
    const MeshData m = strip(p, "strip");
    expectWellFormed(m, "strip");
    const int nAlong = 9;
    EXPECT_EQ(m.points.size(), static_cast<std::size_t>(nAlong * 4));
    EXPECT_EQ(m.triangles.size(), static_cast<std::size_t>(2 * (nAlong - 1) * 3));
    EXPECT_NEAR(totalArea(m), 0.5 * 2 * std::sqrt(1.25), 1e-12);
    EXPECT_TRUE(coincidentPairs(m).empty());
    // Normal = along x w, segment by segment (triangles come two per square, along the path first).
    for (int t = 0; t < static_cast<int>(m.triangles.size()); ++t) {
      const int square = t / 2;
      const int segment = (square % (nAlong - 1)) / 4;
      expectOriented(m, {t}, cross(sub(p.path[segment + 1], p.path[segment]), p.width));
    }
    const auto& start = m.nodeGroups.at("start");
    const auto& end = m.nodeGroups.at("end");
    ASSERT_EQ(start.size(), 4u);
    ASSERT_EQ(end.size(), 4u);
    for (int j = 0; j < 4; ++j) {
      EXPECT_EQ(m.points[start[j]], (Point3{-1, 0.5 * j / 3, 0}));
      EXPECT_EQ(m.points[end[j]], (Point3{1, 0.5 * j / 3, 0}));
    }
    const auto& side0 = m.nodeGroups.at("side0");
    const auto& side1 = m.nodeGroups.at("side1");
    ASSERT_EQ(side0.size(), static_cast<std::size_t>(nAlong));
    ASSERT_EQ(side1.size(), static_cast<std::size_t>(nAlong));
    for (int i = 0; i < nAlong; ++i) {
      EXPECT_EQ(m.points[side0[i]][1], 0.0);
      EXPECT_EQ(m.points[side1[i]][1], 0.5);
      EXPECT_EQ(m.points[side1[i]][0], m.points[side0[i]][0]);
    }
    EXPECT_EQ(m.points[side0[4]], (Point3{0, 0, -0.5}));
    EXPECT_EQ(m.triangleGroups.at("all").size(), m.triangles.size());
  }
}

TEST(GeneratorPillow, SquareAirbag) {
  PillowParams p;
  p.shape = "rectangle";
  p.rectangle.size = {0.84, 0.84};
  p.rectangle.divisions = {16, 16};
  p.rectangle.pattern = "cross";
  const MeshData m = pillow(p, "airbag");
  expectWellFormed(m, "airbag");
  const std::size_t faceNodes = 17 * 17 + 16 * 16, rimNodes = 4 * 16;
  EXPECT_EQ(m.triangles.size(), 2048u);
  EXPECT_EQ(m.points.size(), 2 * faceNodes - rimNodes);  // 1026
  EXPECT_EQ(m.nodeGroups.at("rim").size(), rimNodes);
  EXPECT_EQ(m.nodeGroups.at("top").size(), faceNodes);
  EXPECT_EQ(m.nodeGroups.at("bottom").size(), faceNodes);
  const auto& topTriangles = m.triangleGroups.at("top");
  const auto& bottomTriangles = m.triangleGroups.at("bottom");
  EXPECT_EQ(topTriangles.size(), 1024u);
  EXPECT_EQ(bottomTriangles.size(), 1024u);
  EXPECT_EQ(m.triangleGroups.at("all").size(), 2048u);
  expectOriented(m, topTriangles, {0, 0, 1});
  expectOriented(m, bottomTriangles, {0, 0, -1});
  EXPECT_NEAR(totalArea(m), 2 * 0.84 * 0.84, 1e-12);
  expectClosedOrientedSurface(m);

  // Faces use their own node sets, meeting only on the rim.
  const auto nodesOf = [&](const std::vector<int>& triangles) {
    std::set<int> nodes;
    for (const int t : triangles) nodes.insert(m.triangles[t].begin(), m.triangles[t].end());
    return nodes;
  };
  const std::set<int> top = nodesOf(topTriangles), bottom = nodesOf(bottomTriangles);
  EXPECT_EQ(std::vector<int>(top.begin(), top.end()), m.nodeGroups.at("top"));
  EXPECT_EQ(std::vector<int>(bottom.begin(), bottom.end()), m.nodeGroups.at("bottom"));
  std::vector<int> shared;
  std::set_intersection(top.begin(), top.end(), bottom.begin(), bottom.end(), std::back_inserter(shared));
  EXPECT_EQ(shared, m.nodeGroups.at("rim"));

  // The only coincident nodes are the interior top/bottom twins.
  const auto pairs = coincidentPairs(m);
  EXPECT_EQ(pairs.size(), faceNodes - rimNodes);
  for (const auto& [a, b] : pairs) {
    EXPECT_TRUE(top.count(a) && !bottom.count(a)) << a;
    EXPECT_TRUE(bottom.count(b) && !top.count(b)) << b;
  }
  for (const auto& q : m.points) EXPECT_EQ(q[2], 0.0);

  const auto& topCentre = m.nodeGroups.at("top_center");
  const auto& bottomCentre = m.nodeGroups.at("bottom_center");
  ASSERT_EQ(topCentre.size(), 1u);
  ASSERT_EQ(bottomCentre.size(), 1u);
  EXPECT_EQ(m.points[topCentre[0]], (Point3{0, 0, 0}));
  EXPECT_EQ(m.points[bottomCentre[0]], (Point3{0, 0, 0}));
  EXPECT_TRUE(top.count(topCentre[0]) && !bottom.count(topCentre[0]));
  EXPECT_TRUE(bottom.count(bottomCentre[0]) && !top.count(bottomCentre[0]));
}

TEST(GeneratorPillow, DiscCushion) {
  PillowParams p;
  p.shape = "disc";
  p.disc.radius = 0.3;
  p.disc.rings = 4;
  p.disc.center = {0, 0, 1.5};
  const MeshData m = pillow(p, "cushion");
  expectWellFormed(m, "cushion");
  EXPECT_EQ(m.points.size(), 2u * 61u - 24u);
  EXPECT_EQ(m.triangles.size(), 2u * 96u);
  EXPECT_EQ(m.nodeGroups.at("rim").size(), 24u);
  expectOriented(m, m.triangleGroups.at("top"), {0, 0, 1});
  expectOriented(m, m.triangleGroups.at("bottom"), {0, 0, -1});
  expectClosedOrientedSurface(m);
  EXPECT_EQ(coincidentPairs(m).size(), 61u - 24u);
  EXPECT_EQ(m.nodeGroups.at("top_center"), std::vector<int>{0});
  const int bottomCentre = m.nodeGroups.at("bottom_center").at(0);
  EXPECT_NE(bottomCentre, 0);
  EXPECT_EQ(m.points[bottomCentre], (Point3{0, 0, 1.5}));
}

TEST(GeneratorPillow, CentreNodeOnlyWhereOneExists) {
  PillowParams p;
  p.rectangle.divisions = {3, 3};
  p.rectangle.pattern = "ruled";
  EXPECT_EQ(pillow(p).nodeGroups.count("top_center"), 0u);
  p.rectangle.pattern = "cross";
  const MeshData crossed = pillow(p);
  ASSERT_EQ(crossed.nodeGroups.count("top_center"), 1u);
  EXPECT_EQ(crossed.points[crossed.nodeGroups.at("top_center")[0]], (Point3{0, 0, 0}));
  EXPECT_EQ(crossed.points[crossed.nodeGroups.at("bottom_center")[0]], (Point3{0, 0, 0}));
}

TEST(GeneratorErrors, InvalidParametersNameGeneratorAndParameter) {
  RectangleParams r;
  r.size = {0.0, 1.0};
  expectInputError([&] { rectangle(r); }, {"rectangle", "size"});
  r = {};
  r.size = {1.0, std::nan("")};
  expectInputError([&] { rectangle(r); }, {"rectangle", "size"});
  r = {};
  r.divisions = {2, 0};
  expectInputError([&] { rectangle(r); }, {"rectangle", "divisions"});
  r = {};
  r.pattern = "diagonal";
  expectInputError([&] { rectangle(r); }, {"rectangle", "pattern", "diagonal"});
  r = {};
  r.divisions = {2'000'000'000, 2'000'000'000};
  expectInputError([&] { rectangle(r); }, {"rectangle", "divisions"});

  expectInputError([] { disc({-1.0, 3}); }, {"disc", "radius"});
  expectInputError([] { disc({1.0, 0}); }, {"disc", "rings"});

  expectInputError([] { sphereOctant({0.0, 3}); }, {"sphereOctant", "radius"});
  expectInputError([] { sphereOctant({1.0, -2}); }, {"sphereOctant", "divisions"});

  CableChainParams c;
  c.points = {{0, 0, 0}};
  expectInputError([&] { cableChain(c); }, {"cableChain", "points"});
  c.points = {{0, 0, 0}, {1, 0, 0}, {1, 0, 0}};
  expectInputError([&] { cableChain(c); }, {"cableChain", "points", "coincide"});
  c.points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  c.divisions = {1, 2, 3};
  expectInputError([&] { cableChain(c); }, {"cableChain", "divisions"});
  c.divisions = {1, 0};
  expectInputError([&] { cableChain(c); }, {"cableChain", "divisions"});

  StripParams s;
  s.path = {{0, 0, 0}, {1, 0, 0}};
  s.width = {2, 0, 0};
  expectInputError([&] { strip(s); }, {"strip", "width", "parallel"});
  s.width = {0, 0, 0};
  expectInputError([&] { strip(s); }, {"strip", "width"});
  s.width = {0, 1, 0};
  s.across = 0;
  expectInputError([&] { strip(s); }, {"strip", "across"});
  s.across = 1;
  s.pattern = "cross";
  expectInputError([&] { strip(s); }, {"strip", "pattern"});
  s.pattern = "ruled";
  s.path = {};
  expectInputError([&] { strip(s); }, {"strip", "path"});

  PillowParams p;
  p.shape = "sphere";
  expectInputError([&] { pillow(p); }, {"pillow", "shape", "sphere"});
  p.shape = "disc";
  p.disc.rings = 0;
  expectInputError([&] { pillow(p); }, {"pillow", "disc.rings"});
  p.shape = "rectangle";
  p.rectangle.size = {1.0, -1.0};
  expectInputError([&] { pillow(p); }, {"pillow", "rectangle.size"});
}

}  // namespace
}  // namespace fsi::structure
