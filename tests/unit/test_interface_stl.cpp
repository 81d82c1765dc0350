// writeInterfaceStl: the skin a remeshed run snaps its new fluid mesh to (coupling/interface/InterfaceIO).
// Checked against what the surface must be: every vertex at its point plus its displacement, the polygons'
// area kept, and the facets facing out of the body, i.e. against OpenFOAM's patch normals.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "coupling/interface/InterfaceIO.hpp"

namespace {

using fsi::coupling::InterfaceMesh;
using Vec = std::array<double, 3>;

struct Facet {
  Vec normal;
  std::array<Vec, 3> v;
};

std::vector<Facet> readAsciiStl(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<Facet> out;
  std::string word;
  while (in >> word) {
    if (word == "facet") {
      Facet f{};
      in >> word >> f.normal[0] >> f.normal[1] >> f.normal[2];
      in >> word >> word;  // outer loop
      for (auto& v : f.v) in >> word >> v[0] >> v[1] >> v[2];
      out.push_back(f);
    }
  }
  return out;
}

Vec cross(const Vec& a, const Vec& b, const Vec& c) {
  const Vec u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

// A unit square (one quad, counter-clockwise about +z: an OpenFOAM patch face whose normal points out of
// the fluid, i.e. +z into a body lying above it) and a triangle beside it, in the plane z = 0.
InterfaceMesh squareAndTriangle() {
  InterfaceMesh m;
  m.name = "wing";
  m.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}};
  m.addFace({0, 1, 2, 3});
  m.addFace({1, 4, 2});
  return m;
}

class InterfaceStl : public ::testing::Test {
 protected:
  std::filesystem::path dir = std::filesystem::temp_directory_path() / "fsi_interface_stl_test";
  void SetUp() override { std::filesystem::create_directories(dir); }
  void TearDown() override { std::filesystem::remove_all(dir); }
};

TEST_F(InterfaceStl, MovesEveryPointKeepsTheAreaAndFacesOutOfTheBody) {
  const InterfaceMesh m = squareAndTriangle();
  // A rigid rotation by 90 degrees about z plus a lift of 0.5: the written surface must be that image.
  std::vector<double> d;
  for (const auto& p : m.points) {
    d.push_back(-p[1] - p[0]);
    d.push_back(p[0] - p[1]);
    d.push_back(0.5);
  }
  const auto file = dir / "wing.stl";
  fsi::coupling::writeInterfaceStl(m, d, file);
  const std::vector<Facet> facets = readAsciiStl(file);
  ASSERT_EQ(facets.size(), 4U + 1U);  // the quad as the fan about its centre, the triangle as it is
  double area = 0;
  for (const Facet& f : facets) {
    for (const Vec& v : f.v) {
      EXPECT_NEAR(v[2], 0.5, 1e-12);
      // The image of the square or the triangle: x in [-1, 0], y in [0, 2].
      EXPECT_GE(v[0], -1 - 1e-12);
      EXPECT_LE(v[0], 1e-12);
      EXPECT_GE(v[1], -1e-12);
      EXPECT_LE(v[1], 2 + 1e-12);
    }
    const Vec n = cross(f.v[0], f.v[1], f.v[2]);
    area += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    // The patch normal was +z (into the body); the STL's faces out of it, -z, in its vertex order and in its
    // normal line.
    EXPECT_LT(n[2], 0);
    EXPECT_NEAR(f.normal[2], -1.0, 1e-9);
  }
  EXPECT_NEAR(area, 1.0 + 0.5, 1e-12);
}

TEST_F(InterfaceStl, WithoutDisplacementWritesTheMeshAsItIs) {
  const auto file = dir / "flat.stl";
  fsi::coupling::writeInterfaceStl(squareAndTriangle(), {}, file);
  const std::vector<Facet> facets = readAsciiStl(file);
  ASSERT_EQ(facets.size(), 5U);
  // The quad's fan vertex is its centre.
  bool centre = false;
  for (const Facet& f : facets)
    for (const Vec& v : f.v)
      centre = centre || (std::abs(v[0] - 0.5) < 1e-12 && std::abs(v[1] - 0.5) < 1e-12);
  EXPECT_TRUE(centre);
  std::ifstream in(file);
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(first, "solid wing");
}

TEST_F(InterfaceStl, BadCallsAreClearErrors) {
  const InterfaceMesh m = squareAndTriangle();
  EXPECT_THROW(fsi::coupling::writeInterfaceStl(m, std::vector<double>(7, 0.0), dir / "x.stl"),
               std::invalid_argument);
  try {
    fsi::coupling::writeInterfaceStl(m, {}, dir / "no" / "such" / "dir" / "x.stl");
    FAIL() << "an unwritable file was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("x.stl"), std::string::npos) << e.what();
  }
}

TEST_F(InterfaceStl, ReadsBackWhatItWroteWithSharedVerticesMerged) {
  const InterfaceMesh m = squareAndTriangle();
  const auto file = dir / "round.stl";
  fsi::coupling::writeInterfaceStl(m, {}, file);
  const InterfaceMesh back = fsi::coupling::readStlSurface(file);
  // 5 points + the quad's fan centre; 4 + 1 triangles.
  EXPECT_EQ(back.numPoints(), 6);
  ASSERT_EQ(back.numFaces(), 5);
  double area = 0;
  for (int f = 0; f < back.numFaces(); ++f) area += back.faceArea(f);
  EXPECT_NEAR(area, 1.5, 1e-12);
  // The fluid side's orientation again: the first triangle (the quad's fan) faces +z like the patch face.
  const int* v = back.face(0);
  const Vec n =
      cross(back.points[std::size_t(v[0])], back.points[std::size_t(v[1])], back.points[std::size_t(v[2])]);
  EXPECT_GT(n[2], 0);
  // Written again, it is the same surface: the same facets, facing out of the body.
  const auto again = dir / "again.stl";
  fsi::coupling::writeInterfaceStl(back, {}, again);
  const std::vector<Facet> facets = readAsciiStl(again);
  ASSERT_EQ(facets.size(), 5U);
  for (const Facet& f : facets) EXPECT_LT(cross(f.v[0], f.v[1], f.v[2])[2], 0);
}

TEST_F(InterfaceStl, BadStlFilesNameTheFileAndLine) {
  auto expectError = [&](const std::string& text, const std::string& needle) {
    const auto file = dir / "bad.stl";
    std::ofstream(file) << text;
    try {
      fsi::coupling::readStlSurface(file);
      FAIL() << "accepted: " << text;
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  expectError("\x50\x4b binary junk\n", "bad.stl:1: not an ASCII STL");
  expectError("solid s\nfacet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0\n", "bad.stl:5:");
  expectError("solid s\nfacet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 nan\n", "bad.stl:5:");
  expectError("solid s\n  vertex 0 0 0\n  vertex 1 0 0\nendsolid s\n", "not 3");
  expectError("solid s\nendsolid s\n", "no facets");
  EXPECT_THROW(fsi::coupling::readStlSurface(dir / "missing.stl"), std::exception);
}

}  // namespace
