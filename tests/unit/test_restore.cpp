// CentralDifference's two ways back to a saved state: restore(checkpoint) returns to it exactly (ledger and
// step estimate as they were), restore(x, v, t, dt, steps) starts the bookkeeping again at it (a restart
// file).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <thread>
#include <vector>

#include "TestScenes.hpp"
#include "structure/integrate/CentralDifference.hpp"
#include "structure/io/ResultsWriter.hpp"
#include "structure/io/StateFile.hpp"
#include "structure/run/Simulation.hpp"
#include "structure/scene/Scene.hpp"

using namespace fsi::structure;
namespace fs = std::filesystem;

namespace {

// The pressurised Hencky membrane some steps into its inflation: strained, moving, its step estimate changing
// with the stretch.
struct Inflating {
  Scene scene = loadScene(fs::path(FSI_SOURCE_DIR) / "cases/structure/hencky/scene.yaml");
  CentralDifference cd{*scene.model, scene.effectList(), scene.constraints, scene.time.integrator};
  void steps(int n) {
    for (int i = 0; i < n; ++i) ASSERT_TRUE(cd.step(1.0, (cd.steps() + 1) % 10 == 0));
  }
};

}  // namespace

// The old restart kept the strain energy of the state it left (0 from the reset ledger): the restored run
// reported U = 0 and a viscous dissipation equal to the whole strain energy until its next monitoring step,
// and the step estimate of the state it left.
TEST(CentralDifferenceRestore, RestartStartsTheLedgerAtTheRestoredState) {
  Inflating run;
  run.steps(200);
  run.cd.evaluateForces(true);  // strain energy and step estimate of this very state
  const double U = run.cd.energy().strain, stable = run.cd.stableDt();
  ASSERT_GT(U, 0.0);
  const Nodes& N = run.scene.model->nodes;
  const std::vector<double> x = N.x, v = N.v;
  const double t = run.cd.time(), dt = run.cd.lastDt();
  const long n = run.cd.steps();
  run.steps(300);
  ASSERT_NE(run.cd.stableDt(), stable);  // the state left has another estimate

  run.cd.restore(x, v, t, dt, n);
  const EnergyLedger& E = run.cd.energy();
  EXPECT_DOUBLE_EQ(E.initialStrain, U);
  EXPECT_DOUBLE_EQ(E.strain, U);
  EXPECT_NEAR(E.viscousDissipation(), 0.0, 1e-12 * U);
  EXPECT_NEAR(E.created(), 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(run.cd.stableDt(), stable);
  EXPECT_EQ(run.cd.time(), t);
  EXPECT_EQ(run.cd.steps(), n);
}

// A checkpoint returns to the bookkeeping as it was, every ledger field and the step estimate (the old
// restore kept the estimate of the state it left), and the run goes on exactly as it did the first time.
TEST(CentralDifferenceRestore, CheckpointReturnsToTheLedgerAndStepEstimateAsTheyWere) {
  Inflating run;
  run.steps(200);
  const auto saved = run.cd.checkpoint();
  const auto ledger = run.cd.energy().values();
  const double stable = run.cd.stableDt();
  run.steps(100);
  const std::vector<double> x100 = run.scene.model->nodes.x;
  const auto ledger100 = run.cd.energy().values();
  ASSERT_NE(run.cd.stableDt(), stable);

  run.cd.restore(saved);
  EXPECT_EQ(run.cd.energy().values(), ledger);
  EXPECT_EQ(run.cd.stableDt(), stable);
  run.steps(100);
  EXPECT_EQ(run.scene.model->nodes.x, x100);
  EXPECT_EQ(run.cd.energy().values(), ledger100);
}

// A run stopped on request and continued from its interrupted_state.h5 (RunOptions::startState: `fsi run
// --start-from`) into its own directory ends where the run that was never stopped ends — to 1e-12 of the
// deflection (measured: bit for bit) — and its results series goes on from the state's frame.
TEST(CentralDifferenceRestore, ARunContinuedFromItsInterruptedStateEndsAsTheUninterruptedOne) {
  const std::vector<std::string> sets{"meshes.disc.generator.rings=24", "output.interval=0.001",
                                      "time.until_static.max_time=0.004",
                                      "time.until_static.tolerance=1.0e-300"};
  const fs::path scene = fs::path(FSI_SOURCE_DIR) / "cases/structure/hencky/scene.yaml";
  RunOptions opt;
  opt.quiet = true;
  Scene whole = loadScene(scene, sets);
  opt.outDir = fsi::test::outDir("restore-whole");
  const RunResult a = runSimulation(whole, opt);
  ASSERT_EQ(a.reason, StopReason::NotConverged);

  // A stop requested from another thread some ms into the run: on a busy machine it may come during the
  // set-up (a state at t = 0) or after the end; the delay grows until it lands inside the step loop.
  StateSnapshot state;
  for (const int ms : {30, 80, 200, 10}) {
    StopToken stop;
    Scene first = loadScene(scene, sets);
    opt.outDir = fsi::test::outDir("restore-continued");
    opt.stop = &stop;
    std::thread later([&stop, ms] {
      std::this_thread::sleep_for(std::chrono::milliseconds(ms));
      stop.request();
    });
    const RunResult b = runSimulation(first, opt);
    later.join();
    if (b.reason != StopReason::Interrupted) continue;
    state = readState(opt.outDir / "interrupted_state.h5");
    if (state.time > 0.0) break;
  }
  if (!(state.time > 0.0)) GTEST_SKIP() << "no stop landed inside the step loop (busy machine)";

  Scene second = loadScene(scene, sets);
  opt.stop = nullptr;
  opt.startState = state;
  opt.continueSeries = true;
  const RunResult c = runSimulation(second, opt);
  EXPECT_EQ(c.reason, StopReason::NotConverged);
  EXPECT_EQ(c.summary["stats"]["steps"], a.summary["stats"]["steps"]);
  const double w = std::abs(a.probes.at("center_deflection"));
  for (const auto& [k, v] : a.probes) EXPECT_NEAR(c.probes.at(k), v, 1e-12 * std::abs(v)) << k;
  const Nodes& A = whole.model->nodes;
  const Nodes& C = second.model->nodes;
  for (std::size_t d = 0; d < A.x.size(); ++d) ASSERT_NEAR(C.x[d], A.x[d], 1e-12 * w) << d;
  // The series: the first run's frames up to the state, the state's frame, then the continuation's.
  const ResultsFrame last = readLastFrame(opt.outDir / "results.h5");
  EXPECT_EQ(last.time, second.time.endTime);
  EXPECT_EQ(last.stepNumber, c.summary["stats"]["steps"].get<long long>());
}
