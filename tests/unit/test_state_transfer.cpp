// StateTransfer (fsi run --start-from): a displacement field linear on the source's elements is reproduced
// exactly at the nodes of a finer mesh of the same geometry (membrane and cable nodes); a thin wedge's nodes
// take their own skin's displacement, not the nearer opposite skin's; a node off the source's geometry is a
// located error; and readLastFrame reads back what ResultsWriter wrote.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "coupling/mapping/StateTransfer.hpp"
#include "structure/io/ResultsWriter.hpp"
#include "structure/model/Error.hpp"
#include "structure/scene/Scene.hpp"

using fsi::coupling::StateTransferReport;
using fsi::coupling::transferDisplacement;
using fsi::structure::Model;
using fsi::structure::ResultsFrame;

namespace {

// A 1 m square sheet and a cable hanging from its centre, `sheet` × `sheet` cells and `chain` cables.
std::string sheetAndCable(int sheet, int chain) {
  return "materials:\n  film: {type: membrane, young: 1.0e6, poisson: 0.3, thickness: 1.0e-3, density: "
         "1000}\n"
         "  rope: {type: cable, young: 1.0e9, area: 1.0e-6, density: 1000}\n"
         "meshes:\n  sheet:\n    generator: {type: rectangle, size: [1, 1], divisions: [" +
         std::to_string(sheet) + ", " + std::to_string(sheet) +
         "]}\n    material: film\n  rope:\n    generator: {type: cable_chain, points: [[0, 0, 0], [0, 0, "
         "-1]], "
         "divisions: [" +
         std::to_string(chain) + "]}\n    cable_material: rope\ntime: {end: 1.0e-3}\n";
}

std::array<double, 3> linearField(const double* X) {
  return {0.01 + 0.2 * X[0] - 0.1 * X[1] + 0.05 * X[2], -0.02 + 0.3 * X[1] + 0.1 * X[2],
          0.03 - 0.15 * X[0] + 0.25 * X[1] - 0.2 * X[2]};
}

// The model's state with displacement f(X) as a results frame.
template <class F>
ResultsFrame frameOf(const Model& m, F&& f) {
  ResultsFrame r;
  for (int e = 0; e < m.membranes.count; ++e)
    r.triangles.push_back(
        {m.membranes.conn[3 * e], m.membranes.conn[3 * e + 1], m.membranes.conn[3 * e + 2]});
  for (int e = 0; e < m.cables.count; ++e)
    r.lines.push_back({m.cables.conn[2 * e], m.cables.conn[2 * e + 1]});
  for (int i = 0; i < m.nodes.count; ++i) {
    const auto u = f(&m.nodes.X[3 * i]);
    for (int k = 0; k < 3; ++k) {
      r.displacement.push_back(u[k]);
      r.coordinates.push_back(m.nodes.X[3 * i + k] + u[k]);
    }
  }
  return r;
}

}  // namespace

TEST(StateTransfer, LinearFieldIsReproducedOnAFinerMesh) {
  const auto coarse = fsi::structure::loadSceneFromString(sheetAndCable(2, 2), "coarse.yaml");
  const auto fine = fsi::structure::loadSceneFromString(sheetAndCable(6, 5), "fine.yaml");
  StateTransferReport rep;
  const auto u = transferDisplacement(frameOf(*coarse.model, linearField), *fine.model, "coarse", -1.0, &rep);
  const auto& N = fine.model->nodes;
  for (int i = 0; i < N.count; ++i) {
    const auto want = linearField(&N.X[3 * i]);
    for (int k = 0; k < 3; ++k)
      ASSERT_NEAR(u[3 * i + k], want[k], 1e-14) << "node " << i << " component " << k;
  }
  EXPECT_EQ(rep.membraneNodes, 49);  // the 7 × 7 sheet nodes
  EXPECT_EQ(rep.cableNodes, N.count - 49);
  EXPECT_EQ(rep.pointNodes, 0);
  EXPECT_LT(rep.largestDistance, 1e-14);
}

TEST(StateTransfer, AWedgesNodesTakeTheirOwnSkinsDisplacement) {
  // Two skins 1 mm apart (a trailing-edge wedge) meshed coarse and fine, each skin facing outward; the
  // displacement differs between them. A fine node of the lower skin sits 0.1 mm off its coarse facet (a
  // facet's sag) but 0.9 mm from the upper one: either rule finds its own skin. Moving the fine lower skin up
  // by 0.6 mm puts it nearer the upper skin: only the facing rule still finds the lower one.
  auto wedge = [](int n, double lowerShift) {
    std::string y =
        "materials:\n  film: {type: membrane, young: 1.0e6, poisson: 0.3, thickness: 1.0e-3, "
        "density: 1000}\nmeshes:\n";
    y += "  upper:\n    generator: {type: rectangle, size: [1, 1], divisions: [" + std::to_string(n) + ", " +
         std::to_string(n) + "], center: [0, 0, 0.001]}\n    material: film\n";
    y += "  lower:\n    generator: {type: rectangle, size: [1, 1], divisions: [" + std::to_string(n) + ", " +
         std::to_string(n) + "], center: [0, 0, " + std::to_string(lowerShift) + "]}\n    material: film\n";
    return fsi::structure::loadSceneFromString(y + "time: {end: 1.0e-3}\n", "wedge.yaml");
  };
  // The mesh of the lowest node is the lower skin; its triangles are flipped to face down (outward), as a
  // closed body's would.
  auto lowerSkinFacingDown = [](Model& m) {
    int lowest = 0;
    for (int i = 1; i < m.nodes.count; ++i)
      if (m.nodes.X[3 * std::size_t(i) + 2] < m.nodes.X[3 * std::size_t(lowest) + 2]) lowest = i;
    const int lowerMesh = m.nodes.mesh[std::size_t(lowest)];
    for (int e = 0; e < m.membranes.count; ++e)
      if (m.nodes.mesh[std::size_t(m.membranes.conn[3 * e])] == lowerMesh)
        std::swap(m.membranes.conn[3 * e + 1], m.membranes.conn[3 * e + 2]);
    return lowerMesh;
  };
  auto coarse = wedge(2, 0.0);
  Model& cm = *coarse.model;
  lowerSkinFacingDown(cm);
  const ResultsFrame source = frameOf(cm, [](const double* X) {
    return std::array<double, 3>{0, 0, X[2] > 0.0005 ? 0.1 : -0.1};
  });
  for (const double shift : {0.0001, 0.0007}) {
    auto fine = wedge(4, shift);
    Model& fm = *fine.model;
    const int lowerMesh = lowerSkinFacingDown(fm);
    const auto u = transferDisplacement(source, fm, "coarse");
    for (int i = 0; i < fm.nodes.count; ++i) {
      const bool lower = fm.nodes.mesh[std::size_t(i)] == lowerMesh;
      ASSERT_DOUBLE_EQ(u[3 * std::size_t(i) + 2], lower ? -0.1 : 0.1) << "shift " << shift << ", node " << i;
    }
  }
}

TEST(StateTransfer, ANodeOffTheSourceGeometryIsALocatedError) {
  const auto coarse = fsi::structure::loadSceneFromString(sheetAndCable(2, 2), "coarse.yaml");
  auto other = fsi::structure::loadSceneFromString(sheetAndCable(3, 2), "other.yaml");
  for (int i = 0; i < other.model->nodes.count; ++i) other.model->nodes.X[3 * i + 2] += 0.5;  // 0.5 m higher
  try {
    transferDisplacement(frameOf(*coarse.model, linearField), *other.model, "--start-from old/results.h5");
    FAIL() << "no error";
  } catch (const fsi::InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("--start-from old/results.h5"), std::string::npos) << m;
    EXPECT_NE(m.find("node "), std::string::npos) << m;
    EXPECT_NE(m.find("not of this model's geometry"), std::string::npos) << m;
  }
}

TEST(StateTransfer, ReadLastFrameReadsWhatTheWriterWrote) {
  const auto s = fsi::structure::loadSceneFromString(sheetAndCable(2, 2), "coarse.yaml");
  const ResultsFrame f = frameOf(*s.model, linearField);
  const auto dir = std::filesystem::path(FSI_BINARY_DIR) / "unit-test-output" / "state-transfer";
  std::filesystem::create_directories(dir);
  {
    fsi::structure::ResultsWriter w(dir / "results.h5", f.numNodes(), f.triangles, f.lines);
    std::vector<double> zero(f.coordinates.size(), 0.0);
    w.writeStep(0.0, 0, f.coordinates.data(),
                {{"displacement", fsi::structure::FieldView::Center::Node, 3, zero.data(), zero.size()}});
    w.writeStep(1.0, 10, f.coordinates.data(),
                {{"displacement", fsi::structure::FieldView::Center::Node, 3, f.displacement.data(),
                  f.displacement.size()}});
  }
  const ResultsFrame r = fsi::structure::readLastFrame(dir / "results.h5");
  EXPECT_EQ(r.step, "000001");
  EXPECT_EQ(r.time, 1.0);
  EXPECT_EQ(r.triangles, f.triangles);
  EXPECT_EQ(r.lines, f.lines);
  EXPECT_EQ(r.coordinates, f.coordinates);
  EXPECT_EQ(r.displacement, f.displacement);
  EXPECT_THROW(fsi::structure::readLastFrame(dir / "missing.h5"), fsi::InputError);
}

// Every attribute readLastFrame reads is checked for shape and type (issue 35): an array `time` was read
// into one double (a stack overwrite: `fsi run --start-from` died of SIGSEGV), an array `step` was never
// looked at. Each is now an InputError naming the file, the frame and the attribute.
TEST(StateTransfer, ReadLastFrameChecksEveryAttribute) {
  const auto s = fsi::structure::loadSceneFromString(sheetAndCable(2, 2), "coarse.yaml");
  const ResultsFrame f = frameOf(*s.model, linearField);
  const auto dir = std::filesystem::path(FSI_BINARY_DIR) / "unit-test-output" / "state-transfer-attributes";
  std::filesystem::create_directories(dir);
  const double times[3] = {1.0, 2.0, 3.0}, fraction = 1.5, nan = std::nan("");
  const long long steps[2] = {10, 11}, nodes[2] = {1, 2};
  struct Case {
    const char* label;
    const char* object;  // "" the root, else the last frame's group
    const char* attribute;
    hid_t type;
    std::vector<hsize_t> dims;
    const void* data;
    const char* says;
  };
  const Case cases[] = {
      {"time_array", "/steps/000001", "time", H5T_NATIVE_DOUBLE, {3}, times, "found an array of shape (3)"},
      {"time_nan", "/steps/000001", "time", H5T_NATIVE_DOUBLE, {}, &nan, "non-finite"},
      {"step_array", "/steps/000001", "step", H5T_NATIVE_LLONG, {2}, steps, "found an array of shape (2)"},
      {"step_fraction", "/steps/000001", "step", H5T_NATIVE_DOUBLE, {}, &fraction, "expected an integer"},
      {"num_nodes_array", "/", "num_nodes", H5T_NATIVE_LLONG, {2}, nodes, "found an array of shape (2)"},
  };
  for (const Case& c : cases) {
    const auto file = dir / (std::string(c.label) + ".h5");
    {
      fsi::structure::ResultsWriter w(file, f.numNodes(), f.triangles, f.lines);
      std::vector<double> zero(f.coordinates.size(), 0.0);
      for (int i = 0; i < 2; ++i)
        w.writeStep(double(i), 10 * i, f.coordinates.data(),
                    {{"displacement", fsi::structure::FieldView::Center::Node, 3, zero.data(), zero.size()}});
    }
    {
      const hid_t h = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
      ASSERT_GE(h, 0);
      ASSERT_GE(H5Adelete_by_name(h, c.object, c.attribute, H5P_DEFAULT), 0);
      const hid_t space = c.dims.empty() ? H5Screate(H5S_SCALAR)
                                         : H5Screate_simple(int(c.dims.size()), c.dims.data(), nullptr);
      const hid_t a =
          H5Acreate_by_name(h, c.object, c.attribute, c.type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      ASSERT_GE(a, 0);
      ASSERT_GE(H5Awrite(a, c.type, c.data), 0);
      H5Aclose(a);
      H5Sclose(space);
      ASSERT_GE(H5Fclose(h), 0);
    }
    const std::string where = std::string(c.object) == "/" ? std::string("/@") + c.attribute
                                                           : std::string(c.object) + "@" + c.attribute;
    try {
      fsi::structure::readLastFrame(file);
      ADD_FAILURE() << c.label << ": read without an error";
    } catch (const fsi::InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(file.string()), std::string::npos) << c.label << ": " << what;
      EXPECT_NE(what.find("'" + where + "'"), std::string::npos) << c.label << ": " << what;
      EXPECT_NE(what.find(c.says), std::string::npos) << c.label << ": " << what;
    }
  }
}
