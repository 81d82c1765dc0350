// The real structural solver in a coupled loop with a reduced fluid: a drum membrane loaded by an external
// pressure and by the added-mass pressure of a heavy fluid, p = p_ext − m_a·ẅ (m_a: added mass per area).
// Independent reference: the same membrane run alone with its areal mass increased by m_a — the monolithic
// equivalent of the added mass, exact because the nodes move only along the normal (in-plane dofs fixed).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "TestScenes.hpp"
#include "coupling/StructureParticipant.hpp"
#include "coupling/scheme/CouplingScheme.hpp"
#include "coupling/scheme/acceleration/IqnIls.hpp"
#include "structure/run/Simulation.hpp"
#include "structure/scene/Scene.hpp"

using namespace fsi;
using namespace fsi::coupling;

namespace {

const std::string kDrum =
    test::drumScene(R"(  - {nodes: sheet, fix: [x, y]}   # normal motion only: the added mass acts on it alone
coupling: {interface: sheet}
time: {end: 1.0}
)");

constexpr double kPext = 200.0;  // Pa

// Incompressible fluid reduced to its added mass on the normal motion; acceleration from the interface
// displacement history by second differences (the fluid's own time discretisation).
class AddedMassFluid final : public FluidSolver {
 public:
  AddedMassFluid(int nodes, double addedMass, double t0) : n_(nodes), ma_(addedMass), tWindow_(t0) {
    wPrev_ = wCur_ = last_ = Eigen::VectorXd::Zero(3 * nodes);
  }
  Eigen::VectorXd solve(double t, double dt, const Eigen::VectorXd& d) override {
    if (t > tWindow_ + 1e-9 * dt) {  // a new window: the last solved position was accepted
      wPrev_ = wCur_;
      wCur_ = last_;
      tWindow_ = t;
    }
    last_ = d;
    Eigen::VectorXd p(n_);
    for (int i = 0; i < n_; ++i) {
      const double a = (d[3 * i + 2] - 2 * wCur_[3 * i + 2] + wPrev_[3 * i + 2]) / (dt * dt);
      p[i] = kPext - ma_ * a;
    }
    return p;
  }
  void saveCheckpoint() override {}
  void restoreCheckpoint() override {}

 private:
  int n_;
  double ma_, tWindow_;
  Eigen::VectorXd wPrev_, wCur_, last_;
};

struct CoupledRun {
  bool finite = true;
  double centre = 0;  // centre displacement at the end
  double meanIterations = 0;
};

CoupledRun runCoupled(SchemeKind kind, double addedMass, double dt, int windows) {
  StructureParticipant s(structure::loadSceneFromString(kDrum, "drum.yaml"));
  AddedMassFluid fluid(s.numInterfaceNodes(), addedMass, 0.0);
  CouplingConfig cfg;
  cfg.kind = kind;
  cfg.timeWindowSize = dt;
  cfg.endTime = windows * dt;
  cfg.relativeTolerance = 1e-8;
  cfg.maxIterations = 100;
  CouplingScheme scheme(cfg, s, kind == SchemeKind::Implicit ? std::make_unique<IqnIls>() : nullptr);
  const Eigen::VectorXd p0 = Eigen::VectorXd::Constant(s.numInterfaceNodes(), kPext);
  scheme.initialize(0.0, Eigen::VectorXd::Zero(3 * s.numInterfaceNodes()), p0);
  CoupledRun r;
  int centre = 0;
  double best = 1e9;
  for (int i = 0; i < s.numInterfaceNodes(); ++i) {
    const auto& x = s.interfaceMesh().points[i];
    if (x[0] * x[0] + x[1] * x[1] < best) best = x[0] * x[0] + x[1] * x[1], centre = i;
  }
  while (scheme.isCouplingOngoing()) {
    try {
      runTimeWindow(scheme, fluid);
    } catch (const std::runtime_error&) {  // the structure stopped on a non-finite state: unstable
      r.finite = false;
      return r;
    }
    const double w = scheme.acceptedDisplacement()[3 * centre + 2];
    if (!std::isfinite(w) || std::abs(w) > 10.0) {
      r.finite = false;
      return r;
    }
  }
  r.centre = scheme.acceptedDisplacement()[3 * centre + 2];
  r.meanIterations = scheme.statistics().meanIterations();
  return r;
}

double monolithic(double addedMass, double tEnd) {
  // Areal mass ρt + m_a through the density: (1000·1e-3 + m_a)/1e-3.
  const double rho = (1.0 + addedMass) / 1e-3;
  structure::Scene sc = structure::loadSceneFromString(
      kDrum, "drum.yaml",
      {"materials.film.density=" + std::to_string(rho), "effects={pressure: {triangles: sheet, value: 200}}",
       "time.end=" + std::to_string(tEnd)});
  structure::RunOptions opt;
  // One folder per test: ctest runs the tests of this file in parallel processes.
  opt.outDir = std::string(FSI_BINARY_DIR) + "/test-output/coupled-monolithic-" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name();
  opt.quiet = true;
  structure::runSimulation(sc, opt);
  const auto& N = sc.model->nodes;
  int c = 0;
  double best = 1e9;
  for (int i = 0; i < N.count; ++i) {
    const double r2 = N.X[3 * i] * N.X[3 * i] + N.X[3 * i + 1] * N.X[3 * i + 1];
    if (r2 < best) best = r2, c = i;
  }
  return N.x[3 * c + 2] - N.X[3 * c + 2];
}

}  // namespace

TEST(CoupledMembrane, HeavyFluidMakesStaggeredCouplingUnstableButImplicitCouplingMatchesMonolithic) {
  const double ma = 5.0;  // added mass per area 5 kg/m² against the film's 1 kg/m²: ratio 5
  const double dt = 0.25e-3, tEnd = 0.08;
  const int windows = int(std::lround(tEnd / dt));
  const CoupledRun staggered = runCoupled(SchemeKind::Staggered, ma, dt, windows);
  EXPECT_FALSE(staggered.finite) << "a ratio of 5 is far above the staggered scheme's limit";
  const CoupledRun implicit = runCoupled(SchemeKind::Implicit, ma, dt, windows);
  ASSERT_TRUE(implicit.finite);
  const double ref = monolithic(ma, tEnd);
  EXPECT_GT(std::abs(ref), 1e-3);
  EXPECT_NEAR(implicit.centre, ref, 0.02 * std::abs(ref));
  EXPECT_LT(implicit.meanIterations, 30.0);
  std::printf("coupled (IQN-ILS) centre %.6e m, monolithic %.6e m, %.1f iterations per window\n",
              implicit.centre, ref, implicit.meanIterations);
}

TEST(CoupledMembrane, ImplicitCouplingConvergesToTheMonolithicAnswerWithTheStep) {
  const double ma = 5.0, tEnd = 0.08;
  const double ref = monolithic(ma, tEnd);
  const CoupledRun coarse = runCoupled(SchemeKind::Implicit, ma, 1e-3, 80);
  const CoupledRun fine = runCoupled(SchemeKind::Implicit, ma, 0.25e-3, 320);
  ASSERT_TRUE(coarse.finite && fine.finite);
  const double eCoarse = std::abs(coarse.centre - ref), eFine = std::abs(fine.centre - ref);
  std::printf("error vs monolithic: dt 1 ms %.3e, dt 0.25 ms %.3e (ratio %.2f)\n", eCoarse, eFine,
              eCoarse / eFine);
  EXPECT_GT(eCoarse / eFine, 3.0);  // a step 4x smaller: at least first order towards the monolithic answer
}

TEST(CoupledMembrane, LightFluidIsStableStaggered) {
  // μ = 0.1 is below the staggered limit (1/3 with the linear predictor, docs/COUPLING.md): the run stays
  // bounded (an unstable run grows without bound within these 320 windows, as the μ = 5 case shows).
  const CoupledRun staggered = runCoupled(SchemeKind::Staggered, 0.1, 0.25e-3, 320);
  ASSERT_TRUE(staggered.finite);
  EXPECT_LT(std::abs(staggered.centre), 4.0 * std::abs(monolithic(0.1, 0.08)));
}
