// Dynamic relaxation: convergence with defaults on the hard cases, no silent divergence, agreement with the
// explicit solver's static state, and the fictitious-mass bound.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "TestScenes.hpp"
#include "structure/elements/BuildModel.hpp"
#include "structure/elements/MembraneForces.hpp"
#include "structure/integrate/FictitiousMass.hpp"
#include "structure/run/Simulation.hpp"
#include "structure/scene/Generators.hpp"
#include "structure/scene/Scene.hpp"

using namespace fsi::structure;
namespace fs = std::filesystem;

namespace {

using fsi::test::outDir;

RunResult runCase(const std::string& scene, const std::vector<std::string>& sets, const std::string& name) {
  Scene s = loadScene(fs::path(FSI_SOURCE_DIR) / "cases/structure" / scene / "scene.yaml", sets);
  RunOptions opt;
  opt.outDir = outDir(name);
  opt.quiet = true;
  return runSimulation(s, opt);
}

// A flat square sheet clamped on its edges, inflated by a pressure: zero normal stiffness at the start.
const char* kFlatSheet = R"(materials:
  film: {type: membrane, young: 1.0e8, poisson: 0.3, thickness: 1.0e-3, density: 1000}
meshes:
  sheet:
    generator: {type: rectangle, size: [1, 1], divisions: [12, 12], pattern: alternating}
    material: film
constraints:
  - {nodes: sheet/boundary, fix: all}
effects:
  pressure: {triangles: sheet, value: 1000}
solver: {type: dynamic_relaxation}
probes:
  centre: {type: displacement, nodes: {nearest: [0, 0, 0]}, component: z}
)";

RunResult runString(const std::string& yaml, const std::vector<std::string>& sets, const std::string& name) {
  Scene s = loadSceneFromString(yaml, "sheet.yaml", sets);
  RunOptions opt;
  opt.outDir = outDir(name);
  opt.quiet = true;
  return runSimulation(s, opt);
}

}  // namespace

TEST(Relaxation, SquareCushionConvergesWithDefaultsInFewerIterationsThanTheReference) {
  const RunResult r = runCase("cushion-square-25", {}, "dr-cushion25");
  ASSERT_EQ(r.reason, StopReason::Static);
  EXPECT_TRUE(r.summary["stats"]["converged"].get<bool>());
  EXPECT_LE(r.summary["stats"]["final_residual"].get<double>(), 1e-3);
  // Reference best count on this mesh (TL1, 2028 dof): 518 (kinetic DR, proposal-2 masses, λ = 0.6).
  EXPECT_LE(r.summary["stats"]["iterations"].get<long>(), 518);
}

TEST(Relaxation, FinerAndCircularCushionsConvergeWithDefaults) {
  for (const char* c : {"cushion-square-50", "cushion-circular"}) {
    const RunResult r = runCase(c, {}, std::string("dr-") + c);
    EXPECT_EQ(r.reason, StopReason::Static) << c;
    EXPECT_LE(r.summary["stats"]["final_residual"].get<double>(), 1e-3) << c;
  }
}

// The reference thesis' membrane carries compression (no wrinkling model). With ours switched off, the
// circular cushion converges with the defaults in fewer iterations than the thesis' best (1542, kinetic DR);
// this count is robust (pressure × (1 + k 1e-12) and λ ± k ulp, |k| ≤ 10, all give 1505), unlike TL2's
// with wrinkling (1218-1804), which no test pins (docs/DYNAMIC_RELAXATION.md, "Iteration counts").
TEST(Relaxation, CircularCushionWithoutWrinklingNeedsFewerIterationsThanTheReference) {
  const RunResult r = runCase("cushion-circular", {"materials.fabric.wrinkling=false"}, "dr-circular-taut");
  ASSERT_EQ(r.reason, StopReason::Static);
  EXPECT_EQ(r.summary["stats"]["restarts"].get<int>(), 0);
  EXPECT_LE(r.summary["stats"]["iterations"].get<long>(), 1542);
}

TEST(Relaxation, FlatStartWithZeroNormalStiffnessConverges) {
  const RunResult r = runString(kFlatSheet, {}, "dr-flat");
  ASSERT_EQ(r.reason, StopReason::Static);
  EXPECT_GT(r.probes.at("centre"), 0.0);  // inflated along +z, the normal of the counter-clockwise mesh
}

TEST(Relaxation, AgreesWithTheExplicitSolverStaticState) {
  // Same sheet, tight tolerance, against damped explicit dynamics run to rest.
  const RunResult dr = runString(kFlatSheet, {"solver.tolerance=1.0e-7"}, "dr-vs-cd-dr");
  const std::string dynamic = std::string(kFlatSheet)
                                  .replace(std::string(kFlatSheet).find("solver:"),
                                           std::string("solver: {type: dynamic_relaxation}").size(),
                                           "time: {until_static: {tolerance: 1.0e-12, max_time: 5}}");
  const RunResult cd = runString(dynamic, {"effects.mass_damping={alpha: 100}"}, "dr-vs-cd-cd");
  ASSERT_EQ(dr.reason, StopReason::Static);
  ASSERT_EQ(cd.reason, StopReason::Static);
  EXPECT_NEAR(dr.probes.at("centre"), cd.probes.at("centre"), 1e-5 * std::abs(cd.probes.at("centre")));
}

TEST(Relaxation, SlackAndWrinkledRegionsConverge) {
  // Edges pulled 2% inwards: the sheet starts slack, and a light pressure leaves wrinkled zones.
  const std::string yaml =
      std::string(kFlatSheet)
          .replace(std::string(kFlatSheet).find("  - {nodes: sheet/boundary, fix: all}"),
                   std::string("  - {nodes: sheet/boundary, fix: all}").size(),
                   "  - {nodes: sheet/xmin, prescribe: {component: x, amplitude: 0.01}}\n"
                   "  - {nodes: sheet/xmax, prescribe: {component: x, amplitude: -0.01}}\n"
                   "  - {nodes: sheet/boundary, fix: [y, z]}");
  const RunResult r = runString(yaml, {"effects.pressure.value=20"}, "dr-slack");
  ASSERT_EQ(r.reason, StopReason::Static) << r.diagnosis;
  Scene s = loadSceneFromString(yaml, "sheet.yaml", {"effects.pressure.value=20"});
  RunOptions opt;
  opt.outDir = outDir("dr-slack2");
  opt.quiet = true;
  runSimulation(s, opt);
  MembraneStressField f;
  membraneStresses(s.model->membranes, s.model->nodes.x.data(), f);
  int wrinkled = 0;
  for (double st : f.state) wrinkled += st == 1.0;
  EXPECT_GT(wrinkled, 0);
}

TEST(Relaxation, IncrementalLoadingInTenStepsConverges) {
  const RunResult one = runCase("cushion-square-25", {}, "dr-inc1");
  const RunResult ten = runCase("cushion-square-25", {"solver.increments=10"}, "dr-inc10");
  ASSERT_EQ(ten.reason, StopReason::Static);
  EXPECT_EQ(ten.summary["stats"]["increments"].get<int>(), 10);
  // Same equilibrium within the tolerance of the criterion.
  EXPECT_NEAR(ten.probes.at("center_displacement"), one.probes.at("center_displacement"),
              5e-3 * one.probes.at("center_displacement"));
}

TEST(Relaxation, TooLightMassesAreCaughtNotSilent) {
  // λ = 0.2 is far below the Gerschgorin bound (0.5). With the safeguards the run recovers and says so;
  // without them it stops as diverged with a message.
  const RunResult safe = runCase("cushion-square-25", {"solver.lambda=0.2"}, "dr-light-safe");
  EXPECT_EQ(safe.reason, StopReason::Static);
  EXPECT_GT(safe.summary["stats"]["restarts"].get<int>() + safe.summary["stats"]["mass_increases"].get<int>(),
            0);
  const RunResult bare =
      runCase("cushion-square-25", {"solver.lambda=0.2", "solver.auto_mass=false"}, "dr-light");
  EXPECT_NE(bare.reason, StopReason::Static);
  EXPECT_NE(bare.exitCode(), 0);
  EXPECT_FALSE(bare.diagnosis.empty());
}

TEST(FictitiousMass, GerschgorinBoundHoldsForTheLargestEigenvalue) {
  // Power iteration on M⁻¹K (K applied element by element through finite differences of the forces is
  // overkill here): compare with the exact largest eigenvalue of a single linear cable, 2 EA/L / m.
  CableChainParams p;
  p.points = {{0, 0, 0}, {1, 0, 0}};
  MeshInput in;
  in.mesh = cableChain(p, "c");
  in.cableMaterial = 0;
  Model m = buildModel({in}, {}, {CableMaterial{"c", 1e9, 1e-4, 1000}});
  m.nodes.x[3 * m.meshes[0].node[1]] = 1.001;  // slightly stretched
  std::vector<double> row, diag;
  tangentStiffnessBounds(m, m.nodes.x.data(), row, diag);
  const double ka = 1e9 * 1e-4 / 1.0;
  // Row sum of [ka −ka; −ka ka] along x: 2 ka (+ the small geometric part in y and z).
  EXPECT_NEAR(row[0], 2 * ka, 1e-9 * ka);
  EXPECT_NEAR(diag[0], ka, 1e-9 * ka);
  const auto mass = fictitiousMasses(m, m.nodes.x.data(), FictitiousMassRule::Gerschgorin, 0.5);
  // ω_max² = eig_max(M⁻¹K) = 2 ka / m must be <= 4 (Δt = 1 stable) at λ = 0.5.
  EXPECT_LE(2 * ka / mass[0], 4.0 + 1e-12);
}
