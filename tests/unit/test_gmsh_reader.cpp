// Gmsh reader: meshes are generated with the Gmsh API into a temporary directory, written in several MSH
// flavours and read back. The writing session is always finalised before readGmsh opens its own.

#include <gmsh.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "structure/io/GmshReader.hpp"
#include "structure/model/Error.hpp"

namespace fsi::structure {
namespace {

namespace fs = std::filesystem;

// Finalises the test's own Gmsh session even when an assertion throws or returns early.
struct WriterSession {
  WriterSession() {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
  }
  ~WriterSession() { gmsh::finalize(); }
  WriterSession(const WriterSession&) = delete;
  WriterSession& operator=(const WriterSession&) = delete;
};

class GmshReaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::random_device rd;
    dir_ = fs::temp_directory_path() / ("fsi_gmsh_test_" + std::to_string(rd()) + std::to_string(rd()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
};

enum class Elements { Triangles, Quads, SecondOrder };

// What the written file must give back.
struct Expected {
  std::size_t nodes = 0;
  std::size_t triangles = 0;         // quads counted twice
  std::multiset<long> triangleTags;  // quad tags twice
  std::multiset<long> edgeLineTags;  // lines of the "edge" group
  std::set<long> edgeNodeTags;       // nodes of the "edge" group
  std::array<double, 3> normal{};    // surface normal of the plane
};

// 2 x 1 rectangle in z = 0 with physical surface "canopy" and physical curve "edge" (y = 0).
// With `secondGroup`, the surface is also in physical group "canopy_copy".
Expected writeRectangle(const fs::path& file, double version, bool binary, Elements elements,
                        bool secondGroup = false) {
  WriterSession session;
  gmsh::model::add("rectangle");
  const double lc = 0.3;
  gmsh::model::geo::addPoint(0, 0, 0, lc, 1);
  gmsh::model::geo::addPoint(2, 0, 0, lc, 2);
  gmsh::model::geo::addPoint(2, 1, 0, lc, 3);
  gmsh::model::geo::addPoint(0, 1, 0, lc, 4);
  for (int k = 1; k <= 4; ++k) gmsh::model::geo::addLine(k, k % 4 + 1, k);
  gmsh::model::geo::addCurveLoop({1, 2, 3, 4}, 1);
  gmsh::model::geo::addPlaneSurface({1}, 1);
  gmsh::model::geo::synchronize();
  gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, {1}), "canopy");
  if (secondGroup) gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, {1}), "canopy_copy");
  if (elements != Elements::SecondOrder) {
    gmsh::model::setPhysicalName(1, gmsh::model::addPhysicalGroup(1, {1}), "edge");
  }
  if (elements == Elements::Quads) gmsh::model::mesh::setRecombine(2, 1);
  // Options may outlive a Gmsh session, so set the order every time.
  gmsh::option::setNumber("Mesh.ElementOrder", elements == Elements::SecondOrder ? 2 : 1);
  gmsh::model::mesh::generate(2);

  Expected expected;
  std::vector<double> normal;
  gmsh::model::getNormal(1, {0.5, 0.5}, normal);
  expected.normal = {normal[0], normal[1], normal[2]};
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> tags, nodes;
  gmsh::model::mesh::getElements(types, tags, nodes, 2, 1);
  std::set<std::size_t> used;
  for (std::size_t t = 0; t < types.size(); ++t) {
    const int copies = types[t] == 3 ? 2 : 1;
    for (const auto tag : tags[t]) {
      for (int c = 0; c < copies; ++c) expected.triangleTags.insert(static_cast<long>(tag));
    }
    used.insert(nodes[t].begin(), nodes[t].end());
  }
  expected.triangles = expected.triangleTags.size();
  expected.nodes = used.size();
  gmsh::model::mesh::getElements(types, tags, nodes, 1, 1);
  for (std::size_t t = 0; t < types.size(); ++t) {
    for (const auto tag : tags[t]) expected.edgeLineTags.insert(static_cast<long>(tag));
    for (const auto n : nodes[t]) expected.edgeNodeTags.insert(static_cast<long>(n));
  }

  gmsh::option::setNumber("Mesh.MshFileVersion", version);
  gmsh::option::setNumber("Mesh.Binary", binary ? 1 : 0);
  gmsh::write(file.string());
  return expected;
}

std::array<double, 3> areaVector(const MeshData& m, const std::array<int, 3>& t) {
  const auto& a = m.points[t[0]];
  const auto& b = m.points[t[1]];
  const auto& c = m.points[t[2]];
  const std::array<double, 3> u{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const std::array<double, 3> v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

void checkRectangle(const MeshData& m, const Expected& expected) {
  EXPECT_EQ(m.name, "canopy_mesh");
  ASSERT_EQ(m.points.size(), expected.nodes);
  ASSERT_EQ(m.pointTags.size(), m.points.size());
  ASSERT_EQ(m.triangles.size(), expected.triangles);
  ASSERT_EQ(m.triangleTags.size(), m.triangles.size());
  EXPECT_EQ(std::multiset<long>(m.triangleTags.begin(), m.triangleTags.end()), expected.triangleTags);
  EXPECT_EQ(std::multiset<long>(m.lineTags.begin(), m.lineTags.end()), expected.edgeLineTags);

  double area = 0;
  for (const auto& t : m.triangles) {
    const auto a = areaVector(m, t);
    const double projected =
        a[0] * expected.normal[0] + a[1] * expected.normal[1] + a[2] * expected.normal[2];
    EXPECT_GT(projected, 0.0);
    area += 0.5 * std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  }
  EXPECT_NEAR(area, 2.0, 1e-12);
  for (const auto& p : m.points) {
    EXPECT_TRUE(p[0] >= 0 && p[0] <= 2 && p[1] >= 0 && p[1] <= 1 && p[2] == 0) << p[0] << " " << p[1];
  }

  ASSERT_EQ(m.triangleGroups.count("canopy"), 1u);
  EXPECT_EQ(m.triangleGroups.at("canopy").size(), m.triangles.size());
  ASSERT_EQ(m.nodeGroups.count("canopy"), 1u);
  EXPECT_EQ(m.nodeGroups.at("canopy").size(), m.points.size());
  ASSERT_EQ(m.lineGroups.count("edge"), 1u);
  EXPECT_EQ(m.lineGroups.at("edge").size(), m.lines.size());
  std::set<long> edgeNodes;
  for (const int v : m.nodeGroups.at("edge")) {
    edgeNodes.insert(m.pointTags[v]);
    EXPECT_EQ(m.points[v][1], 0.0);
  }
  EXPECT_EQ(edgeNodes, expected.edgeNodeTags);
}

TEST_F(GmshReaderTest, TrianglesAllFormats) {
  for (const double version : {4.1, 2.2}) {
    for (const bool binary : {false, true}) {
      SCOPED_TRACE(::testing::Message() << "MSH " << version << (binary ? " binary" : " ascii"));
      const fs::path file = dir_ / ("tri_" + std::to_string(version) + (binary ? "b" : "a") + ".msh");
      const Expected expected = writeRectangle(file, version, binary, Elements::Triangles);
      checkRectangle(readGmsh(file, "canopy_mesh"), expected);
    }
  }
}

TEST_F(GmshReaderTest, QuadsSplitIntoTwoTriangles) {
  for (const double version : {4.1, 2.2}) {
    SCOPED_TRACE(version);
    const fs::path file = dir_ / ("quad_" + std::to_string(version) + ".msh");
    const Expected expected = writeRectangle(file, version, false, Elements::Quads);
    const MeshData m = readGmsh(file, "canopy_mesh");
    checkRectangle(m, expected);
    // Each quad became two triangles with the quad's tag, split along the shorter diagonal.
    for (std::size_t t = 0; t < m.triangles.size(); t += 2) {
      ASSERT_EQ(m.triangleTags[t], m.triangleTags[t + 1]);
      std::set<int> quad(m.triangles[t].begin(), m.triangles[t].end());
      quad.insert(m.triangles[t + 1].begin(), m.triangles[t + 1].end());
      ASSERT_EQ(quad.size(), 4u);
      std::array<int, 3> a = m.triangles[t], b = m.triangles[t + 1];
      std::sort(a.begin(), a.end());
      std::sort(b.begin(), b.end());
      std::vector<int> shared;
      std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(shared));
      ASSERT_EQ(shared.size(), 2u);
      std::vector<int> other;
      std::set_symmetric_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(other));
      const auto dist = [&](int i, int j) {
        const auto &p = m.points[i], &q = m.points[j];
        return std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
      };
      EXPECT_LE(dist(shared[0], shared[1]), dist(other[0], other[1]) + 1e-12);
    }
  }
}

TEST_F(GmshReaderTest, Msh22ElementsInTwoGroupsReadOnce) {
  // MSH 2.2 writes such elements once per group, under different tags.
  const fs::path file = dir_ / "two_groups.msh";
  const Expected expected = writeRectangle(file, 2.2, false, Elements::Triangles, true);
  const MeshData m = readGmsh(file, "canopy_mesh");
  EXPECT_EQ(m.triangles.size(), expected.triangles);
  EXPECT_EQ(m.points.size(), expected.nodes);
  EXPECT_EQ(std::set<long>(m.triangleTags.begin(), m.triangleTags.end()).size(), m.triangles.size());
  EXPECT_EQ(m.triangleGroups.at("canopy").size(), m.triangles.size());
  EXPECT_EQ(m.triangleGroups.at("canopy_copy").size(), m.triangles.size());
  EXPECT_EQ(m.nodeGroups.at("canopy_copy").size(), m.points.size());
  EXPECT_EQ(m.lines.size(), expected.edgeLineTags.size());
}

TEST_F(GmshReaderTest, LineMeshWithPointAndUnnamedGroups) {
  const fs::path file = dir_ / "cable.msh";
  {
    WriterSession session;
    gmsh::model::add("cable");
    gmsh::model::geo::addPoint(0, 0, 0, 0.25, 1);
    gmsh::model::geo::addPoint(1, 0, 0, 0.25, 2);
    gmsh::model::geo::addPoint(1, 0, -1, 0.25, 3);
    gmsh::model::geo::addLine(1, 2, 1);
    gmsh::model::geo::addLine(2, 3, 2);
    gmsh::model::geo::synchronize();
    gmsh::model::setPhysicalName(1, gmsh::model::addPhysicalGroup(1, {1}), "cable");
    gmsh::model::addPhysicalGroup(1, {2}, 7);
    gmsh::model::setPhysicalName(0, gmsh::model::addPhysicalGroup(0, {3}), "anchor");
    gmsh::model::mesh::generate(1);
    gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
    gmsh::write(file.string());
  }
  const MeshData m = readGmsh(file, "cable");
  EXPECT_TRUE(m.triangles.empty());
  EXPECT_EQ(m.lines.size(), 8u);
  EXPECT_EQ(m.points.size(), 9u);
  ASSERT_EQ(m.lineTags.size(), m.lines.size());
  ASSERT_EQ(m.lineGroups.count("cable"), 1u);
  ASSERT_EQ(m.lineGroups.count("physical_1_7"), 1u);
  EXPECT_EQ(m.lineGroups.at("cable").size(), 4u);
  EXPECT_EQ(m.lineGroups.at("physical_1_7").size(), 4u);
  EXPECT_EQ(m.nodeGroups.at("cable").size(), 5u);
  EXPECT_EQ(m.nodeGroups.at("physical_1_7").size(), 5u);
  const auto& anchor = m.nodeGroups.at("anchor");
  ASSERT_EQ(anchor.size(), 1u);
  EXPECT_EQ(m.points[anchor[0]], (std::array<double, 3>{1, 0, -1}));
  double length = 0;
  for (const auto& l : m.lines) {
    const auto &p = m.points[l[0]], &q = m.points[l[1]];
    length += std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
  }
  EXPECT_NEAR(length, 2.0, 1e-12);
  // Points are the used nodes in ascending Gmsh tag order.
  EXPECT_TRUE(std::is_sorted(m.pointTags.begin(), m.pointTags.end()));
}

TEST_F(GmshReaderTest, MissingFileNamesPath) {
  const fs::path file = dir_ / "does_not_exist.msh";
  try {
    readGmsh(file, "x");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
}

TEST_F(GmshReaderTest, SecondOrderRejectedWithTypeName) {
  const fs::path file = dir_ / "quadratic.msh";
  writeRectangle(file, 4.1, false, Elements::SecondOrder);
  try {
    readGmsh(file, "x");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    EXPECT_NE(message.find("Triangle 6"), std::string::npos) << message;
    EXPECT_NE(message.find("supported"), std::string::npos) << message;
  }
}

TEST_F(GmshReaderTest, GarbageAndEmptyFilesRejected) {
  const fs::path garbage = dir_ / "garbage.msh";
  std::ofstream(garbage) << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\nnot numbers\n";
  const fs::path pointsOnly = dir_ / "points_only.msh";
  std::ofstream(pointsOnly) << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$EndNodes\n"
                               "$Elements\n1\n1 15 2 0 1 1\n$EndElements\n";
  for (const auto& file : {garbage, pointsOnly, dir_}) {
    try {
      readGmsh(file, "x");
      ADD_FAILURE() << "no InputError for " << file;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    }
  }
  // A failed read leaves no Gmsh session behind: the next read works.
  const fs::path good = dir_ / "good.msh";
  const Expected expected = writeRectangle(good, 4.1, false, Elements::Triangles);
  checkRectangle(readGmsh(good, "canopy_mesh"), expected);
}

}  // namespace
}  // namespace fsi::structure
