// A structure scene's coupling interface as an interface mesh (coupling/interface/SceneInterface): the mesh
// the coupled run uses, and what `fsi map-check SCENE.yaml CASE:patch` checks against the fluid side.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "TestScenes.hpp"
#include "coupling/StructureParticipant.hpp"
#include "coupling/interface/SceneInterface.hpp"
#include "coupling/mapping/MapCheck.hpp"
#include "structure/model/Error.hpp"
#include "structure/model/Model.hpp"

namespace fsi::coupling {
namespace {

namespace fs = std::filesystem;

// The drum (1 m square centred on the origin, 8 x 8 cross-pattern squares: 145 nodes, 256 triangles) with its
// whole sheet as the interface.
const std::string kScene = test::drumScene(R"(coupling: {interface: sheet}
time: {end: 0.1}
)");

std::string sceneWithSecondMesh() {
  // A second mesh, 2 m away, that is not part of the interface.
  std::string s = kScene;
  s.replace(s.find("constraints:"), 0,
            "  other:\n    generator: {type: rectangle, size: [1, 1], divisions: [2, 2], center: [0, 0, 2]}\n"
            "    material: film\n");
  return s;
}

class SceneInterfaceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::random_device rd;
    dir_ = fs::temp_directory_path() / ("fsi_scene_interface_" + std::to_string(rd()) + std::to_string(rd()));
    fs::create_directories(dir_ / "case" / "constant" / "polyMesh");
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path writeScene(const std::string& text, const std::string& name = "structure.yaml") {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  static std::string header(const std::string& cls, const std::string& object) {
    return "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class " + cls + ";\n    object " + object +
           ";\n}\n\n";
  }
  // An OpenFOAM boundary patch `canopy`: nx x ny quadrilaterals on [-0.5, 0.5]^2 at z = 0 (a fluid mesh that
  // does not match the structure's), and a patch `far` of one face elsewhere.
  fs::path writePatch(int nx, int ny) {
    const fs::path mesh = dir_ / "case" / "constant" / "polyMesh";
    std::ofstream points(mesh / "points");
    points << header("vectorField", "points") << (nx + 1) * (ny + 1) + 4 << "\n(\n";
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        points << "(" << -0.5 + double(i) / nx << " " << -0.5 + double(j) / ny << " 0)\n";
    points << "(5 5 5)\n(6 5 5)\n(6 6 5)\n(5 6 5)\n)\n";
    std::ofstream faces(mesh / "faces");
    faces << header("faceList", "faces") << nx * ny + 1 << "\n(\n";
    auto id = [&](int i, int j) { return j * (nx + 1) + i; };
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        faces << "4(" << id(i, j) << " " << id(i + 1, j) << " " << id(i + 1, j + 1) << " " << id(i, j + 1)
              << ")\n";
    const int p0 = (nx + 1) * (ny + 1);
    faces << "4(" << p0 << " " << p0 + 1 << " " << p0 + 2 << " " << p0 + 3 << ")\n)\n";
    std::ofstream(mesh / "boundary") << header("polyBoundaryMesh", "boundary") << "2\n(\n"
                                     << "canopy { type wall; nFaces " << nx * ny << "; startFace 0; }\n"
                                     << "far { type patch; nFaces 1; startFace " << nx * ny << "; }\n)\n";
    return dir_ / "case";
  }
  fs::path dir_;
};

TEST_F(SceneInterfaceTest, IsTheCoupledRunsInterface) {
  const structure::Scene scene = structure::loadSceneFromString(sceneWithSecondMesh(), "two.yaml");
  const InterfaceMesh m = sceneInterface(scene);
  // Only the interface triangles (the sheet), not the second film.
  EXPECT_EQ(m.numPoints(), 9 * 9 + 8 * 8);
  EXPECT_EQ(m.numFaces(), 4 * 8 * 8);
  const auto& nodes = scene.couplingInterface->nodes;
  ASSERT_EQ(std::size_t(m.numPoints()), nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i)  // point i is interface node i, at its reference position
    for (int k = 0; k < 3; ++k) EXPECT_EQ(m.points[i][k], scene.model->nodes.X[3 * nodes[i] + k]);
  for (const auto& p : m.points) EXPECT_LT(std::abs(p[2]), 1e-12);
  // The coupled run sees the same mesh (one code path).
  const StructureParticipant participant(structure::loadSceneFromString(sceneWithSecondMesh(), "two.yaml"));
  const InterfaceMesh& q = participant.interfaceMesh();
  EXPECT_EQ(q.points, m.points);
  EXPECT_EQ(q.faceNodes, m.faceNodes);
  EXPECT_EQ(q.faceOffsets, m.faceOffsets);
}

TEST_F(SceneInterfaceTest, MapsOntoAnOpenFoamPatch) {
  const fs::path scene = writeScene(kScene);
  const fs::path caseDir = writePatch(11, 7);
  const InterfaceMesh structure = readInterfaceOrScene(scene.string());
  const InterfaceMesh fluid = readInterfaceOrScene(caseDir.string() + ":canopy");
  EXPECT_EQ(structure.name, scene.string());
  EXPECT_EQ(fluid.numFaces(), 77);
  MapCheckOptions opt;
  opt.applyRepeats = 1;
  const MapCheckResult r = runMapCheck(structure, fluid, opt);
  ASSERT_TRUE(r.allMapped()) << r.summary();
  for (const DirectionCheck& d : r.directions) {
    // Two planar meshes of one square: the consistent projection reproduces linear fields exactly.
    EXPECT_LT(d.linear.max, 1e-10);
    EXPECT_LT(d.quadratic.max, 5e-2);
    EXPECT_LT(d.forceError, 1e-12);
    EXPECT_LT(d.momentError, 1e-10);
  }
  // Against a patch that covers only a corner of the sheet, the sheet's points are reported unmapped.
  const fs::path small = dir_ / "small";
  fs::create_directories(small / "constant");
  fs::rename(caseDir / "constant" / "polyMesh", small / "constant" / "polyMesh");
  std::ofstream(small / "constant" / "polyMesh" / "points")
      << header("vectorField", "points") << "8\n(\n"
      << "(-0.5 -0.5 0)\n(0 -0.5 0)\n(0 0 0)\n(-0.5 0 0)\n"
      << "(5 5 5)\n(6 5 5)\n(6 6 5)\n(5 6 5)\n)\n";
  std::ofstream(small / "constant" / "polyMesh" / "faces")
      << header("faceList", "faces") << "2\n(\n4(0 1 2 3)\n4(4 5 6 7)\n)\n";
  std::ofstream(small / "constant" / "polyMesh" / "boundary")
      << header("polyBoundaryMesh", "boundary")
      << "2\n(\ncanopy { type wall; nFaces 1; startFace 0; }\nfar { type patch; nFaces 1; startFace 1; "
         "}\n)\n";
  const MapCheckResult bad = runMapCheck(structure, readInterfaceOrScene(small.string() + ":canopy"), opt);
  EXPECT_FALSE(bad.allMapped());
}

TEST_F(SceneInterfaceTest, MapsOntoAGmshSurface) {
  const fs::path scene = writeScene(kScene, "structure.yml");
  // Unstructured Gmsh mesh of the same square (tests/data/gmsh/unstructured_square.geo).
  const fs::path msh = fs::path(FSI_SOURCE_DIR) / "tests" / "data" / "gmsh" / "unstructured_square_41.msh";
  MapCheckOptions opt;
  opt.applyRepeats = 1;
  const MapCheckResult r =
      runMapCheck(readInterfaceOrScene(msh.string() + ":canopy"), readInterfaceOrScene(scene.string()), opt);
  ASSERT_TRUE(r.allMapped()) << r.summary();
  for (const DirectionCheck& d : r.directions) {
    EXPECT_LT(d.linear.max, 1e-10);
    EXPECT_LT(d.forceError, 1e-12);
  }
}

TEST_F(SceneInterfaceTest, OverridesApplyToTheScene) {
  const fs::path scene = writeScene(kScene);
  const InterfaceMesh coarse =
      readInterfaceOrScene(scene.string(), {"meshes.sheet.generator.divisions=[4,4]"});
  EXPECT_EQ(coarse.numPoints(), 5 * 5 + 4 * 4);
  EXPECT_EQ(coarse.numFaces(), 4 * 4 * 4);
}

TEST_F(SceneInterfaceTest, SceneWithoutInterfaceOrFileIsAnInputError) {
  auto expectError = [](const std::string& spec, const std::vector<std::string>& words) {
    try {
      readInterfaceOrScene(spec);
      ADD_FAILURE() << "no error for " << spec;
    } catch (const InputError& e) {
      for (const std::string& w : words)
        EXPECT_NE(std::string(e.what()).find(w), std::string::npos) << e.what();
    }
  };
  const fs::path plain = writeScene(test::drumScene("time: {end: 0.1}\n"), "plain.yaml");
  expectError(plain.string(), {"plain.yaml", "coupling: {interface:"});
  expectError((dir_ / "missing.yaml").string(), {"missing.yaml"});
  // Other forms still go to readInterface.
  expectError((dir_ / "nothing.txt").string(), {"nothing.txt", "CASE_DIR:PATCH", "SCENE.yaml"});
}

}  // namespace
}  // namespace fsi::coupling
