// CentralDifference's two ways back to a saved state: restore(checkpoint) returns to it exactly (ledger and
// step estimate as they were), restore(x, v, t, dt, steps) starts the bookkeeping again at it (a restart
// file).
#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

#include "structure/integrate/CentralDifference.hpp"
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
