// Scene input: clear, located errors for bad input; effects only when enabled; run-level safety nets.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>

#include "TestScenes.hpp"
#include "structure/elements/MembraneForces.hpp"
#include "structure/model/Error.hpp"
#include "structure/run/Simulation.hpp"
#include "structure/scene/Scene.hpp"

using namespace fsi::structure;
namespace fs = std::filesystem;

namespace {

const char* kDrum = R"(title: drum
materials:
  film: {type: membrane, young: 1.0e8, poisson: 0.3, thickness: 1.0e-3, density: 1000}
meshes:
  sheet:
    generator: {type: rectangle, size: [1, 1], divisions: [8, 8], pattern: cross}
    material: film
constraints:
  - {nodes: sheet/boundary, fix: all}
effects:
  pressure: {triangles: sheet, value: 100}
  mass_damping: {alpha: 50}
time:
  end: 0.01
output:
  interval: 0
probes:
  centre: {type: displacement, nodes: {nearest: [0, 0, 0]}, component: z}
)";

std::string errorOf(const std::string& yaml, const std::vector<std::string>& sets = {}) {
  try {
    loadSceneFromString(yaml, "case.yaml", sets);
  } catch (const fsi::InputError& e) {
    return e.what();
  }
  return "";
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  return s.replace(p, from.size(), to);
}

fs::path tempDir(const std::string& name) {
  const fs::path d = fsi::test::outDir(name);  // under the test's own name, emptied
  fs::create_directories(d);
  return d;
}

}  // namespace

TEST(SceneErrors, ValidSceneLoads) {
  Scene s = loadSceneFromString(kDrum, "case.yaml");
  EXPECT_EQ(s.model->membranes.count, 8 * 8 * 4);
  EXPECT_EQ(s.probes.size(), 1u);
}

TEST(SceneErrors, UnknownKeyNamesFileLineKeyAndSuggestion) {
  const std::string e = errorOf(replace(kDrum, "poisson: 0.3", "poison: 0.3"));
  EXPECT_NE(e.find("case.yaml:3:"), std::string::npos) << e;
  EXPECT_NE(e.find("materials.film"), std::string::npos) << e;
  EXPECT_NE(e.find("poisson"), std::string::npos) << e;  // missing required key named
}

TEST(SceneErrors, TypoInEffectSuggestsTheValidName) {
  const std::string e = errorOf(replace(kDrum, "mass_damping:", "mass_dampign:"));
  EXPECT_NE(e.find("case.yaml:12:"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown key 'mass_dampign'"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean 'mass_damping'"), std::string::npos) << e;
  EXPECT_NE(e.find("gravity"), std::string::npos) << e;  // lists the valid choices
}

TEST(SceneErrors, WrongTypeIsReported) {
  const std::string e = errorOf(replace(kDrum, "young: 1.0e8", "young: stiff"));
  EXPECT_NE(e.find("materials.film.young"), std::string::npos) << e;
  EXPECT_NE(e.find("expected a number, got 'stiff'"), std::string::npos) << e;
}

TEST(SceneErrors, MissingReferencesAreNamed) {
  std::string e = errorOf(replace(kDrum, "material: film", "material: flim"));
  EXPECT_NE(e.find("no membrane material named 'flim'"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean 'film'"), std::string::npos) << e;
  e = errorOf(replace(kDrum, "sheet/boundary", "sheet/bondary"));
  EXPECT_NE(e.find("has no group 'bondary'"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean 'boundary'"), std::string::npos) << e;
  e = errorOf(replace(kDrum, "triangles: sheet,", "triangles: canopy,"));
  EXPECT_NE(e.find("no set or mesh named 'canopy'"), std::string::npos) << e;
}

TEST(SceneErrors, ChoicesAreListed) {
  const std::string e = errorOf(replace(kDrum, "pattern: cross", "pattern: diagonal"));
  EXPECT_NE(e.find("'diagonal' is not valid"), std::string::npos) << e;
  EXPECT_NE(e.find("ruled, alternating, cross"), std::string::npos) << e;
}

TEST(SceneErrors, EmptySelectionAndBadValuesAreRefused) {
  std::string e = errorOf(replace(kDrum, "{nodes: sheet/boundary, fix: all}",
                                  "{nodes: {plane: {point: [5, 0, 0], normal: [1, 0, 0]}}, fix: all}"));
  EXPECT_NE(e.find("selects no nodes"), std::string::npos) << e;
  e = errorOf(replace(kDrum, "poisson: 0.3", "poisson: 0.7"));
  EXPECT_NE(e.find("poisson"), std::string::npos) << e;
  EXPECT_NE(e.find("[0, 0.5)"), std::string::npos) << e;
  e = errorOf(kDrum, {"time.end=-1"});
  EXPECT_NE(e.find("must be > 0"), std::string::npos) << e;
}

TEST(SceneErrors, DegenerateElementIsNamed) {
  const fs::path dir = tempDir("degenerate");
  // A Gmsh file with a zero-area triangle (element 2: nodes 1, 2 and a duplicate of node 2).
  std::ofstream(dir / "bad.msh") << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n"
                                    "3 0 1 0\n4 1 0 0\n$EndNodes\n$Elements\n2\n1 2 2 1 1 1 2 3\n"
                                    "2 2 2 1 1 1 2 4\n$EndElements\n";
  std::string yaml =
      replace(kDrum, "generator: {type: rectangle, size: [1, 1], divisions: [8, 8], pattern: cross}",
              "file: bad.msh");
  std::ofstream(dir / "case.yaml") << yaml;
  try {
    loadScene(dir / "case.yaml");
    FAIL() << "degenerate element accepted";
  } catch (const fsi::InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("triangle 2 of mesh 'sheet'"), std::string::npos) << m;
    EXPECT_NE(m.find("degenerate"), std::string::npos) << m;
  }
}

TEST(SceneErrors, YamlSyntaxErrorHasALine) {
  const std::string e = errorOf("materials:\n  a: {type: membrane\n");
  EXPECT_NE(e.find("case.yaml:"), std::string::npos) << e;
  EXPECT_NE(e.find("YAML syntax error"), std::string::npos) << e;
}

TEST(SceneEffects, OnlyEnabledEffectsAreCreated) {
  Scene s = loadSceneFromString(kDrum, "case.yaml");
  std::vector<std::string> names;
  for (const Effect* e : s.effectList()) names.push_back(e->name());
  EXPECT_EQ(names, (std::vector<std::string>{"membrane", "pressure:sheet"}));
  Scene g = loadSceneFromString(kDrum, "case.yaml", {"effects.gravity={acceleration: [0, 0, -9.81]}"});
  EXPECT_EQ(g.effectList().size(), 3u);
}

TEST(Simulation, UnstableRunStopsWithDiagnosisAndKeepsTheLastGoodState) {
  const fs::path out = tempDir("unstable");
  // A fixed step four times the element limit.
  Scene s = loadSceneFromString(kDrum, "case.yaml",
                                {"time.fixed_dt=8.0e-4", "time.end=0.2", "time.monitor_every=10"});
  RunOptions opt;
  opt.outDir = out;
  opt.quiet = true;
  const RunResult r = runSimulation(s, opt);
  EXPECT_EQ(r.reason, StopReason::Unstable);
  EXPECT_EQ(r.exitCode(), 3);
  EXPECT_NE(r.diagnosis.find("node"), std::string::npos) << r.diagnosis;
  EXPECT_NE(r.diagnosis.find("Last stable state"), std::string::npos) << r.diagnosis;
  EXPECT_TRUE(fs::exists(out / "last_good_state.h5"));
  nlohmann::json j;
  std::ifstream(out / "summary.json") >> j;
  EXPECT_EQ(j["stop_reason"], "unstable");
  // The kept state is finite.
  for (const auto& [k, v] : r.probes) EXPECT_TRUE(std::isfinite(v)) << k;
}

TEST(Simulation, AutomaticStepIsStableAndWritesSummary) {
  const fs::path out = tempDir("stable");
  Scene s = loadSceneFromString(kDrum, "case.yaml");
  RunOptions opt;
  opt.outDir = out;
  opt.quiet = true;
  const RunResult r = runSimulation(s, opt);
  EXPECT_EQ(r.reason, StopReason::EndTime);
  nlohmann::json j;
  std::ifstream(out / "summary.json") >> j;
  for (const char* k : {"steps", "simulated_time", "wall_seconds", "element_updates_per_second",
                        "kinetic_energy", "strain_energy", "energy_balance_error"})
    EXPECT_TRUE(j["stats"].contains(k)) << k;
  EXPECT_NEAR(j["stats"]["simulated_time"].get<double>(), 0.01, 1e-12);
  EXPECT_LT(j["stats"]["energy_balance_error"].get<double>(), s.time.energyTolerance);
  EXPECT_TRUE(j["probes"].contains("centre"));
  EXPECT_TRUE(fs::exists(out / "results.xdmf"));
}

TEST(Simulation, CtrlCWritesTheStateAndExitsCleanly) {
  const fs::path out = tempDir("interrupt");
  std::ofstream(out / "case.yaml") << replace(kDrum, "end: 0.01", "end: 1.0e6");
  const std::string cmd = "timeout --preserve-status -s INT 2 " + std::string(FSI_BINARY_DIR) +
                          "/bin/fsi run " + (out / "case.yaml").string() + " --out " +
                          (out / "run").string() + " --quiet > /dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  EXPECT_TRUE(fs::exists(out / "run" / "interrupted_state.h5"));
  nlohmann::json j;
  std::ifstream(out / "run" / "summary.json") >> j;
  EXPECT_EQ(j["stop_reason"], "interrupted");
  EXPECT_GT(j["stats"]["steps"].get<long>(), 0);
}

TEST(Airbag, WrinklesFormAlongTheSeam) {
  const fs::path out = tempDir("airbag");
  Scene s = loadScene(fs::path(FSI_SOURCE_DIR) / "cases/structure/airbag/scene.yaml", {"output.interval=0"});
  RunOptions opt;
  opt.outDir = out;
  opt.quiet = true;
  const RunResult r = runSimulation(s, opt);
  ASSERT_EQ(r.reason, StopReason::Static);
  MembraneStressField f;
  membraneStresses(s.model->membranes, s.model->nodes.x.data(), f);
  int wrinkled = 0, nearSeam = 0;
  const Model& m = *s.model;
  for (int e = 0; e < m.membranes.count; ++e) {
    if (f.state[e] != 1.0) continue;
    ++wrinkled;
    double cx = 0, cy = 0;
    for (int k = 0; k < 3; ++k) {
      cx += m.nodes.X[3 * m.membranes.conn[3 * e + k]] / 3;
      cy += m.nodes.X[3 * m.membranes.conn[3 * e + k] + 1] / 3;
    }
    if (std::max(std::abs(cx), std::abs(cy)) > 0.25) ++nearSeam;
  }
  // Tension-field theory: the bag's rim contracts and buckles; a large share of the elements is wrinkled,
  // mostly in the outer band of each face.
  EXPECT_GT(wrinkled, m.membranes.count / 10);
  EXPECT_GT(nearSeam, wrinkled * 3 / 4);
}
