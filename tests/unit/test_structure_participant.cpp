// The structure as a coupling participant: interface pressure field, subcycling, checkpoints.
#include <gtest/gtest.h>

#include <cmath>

#include "TestScenes.hpp"
#include "coupling/StructureParticipant.hpp"
#include "coupling/mapping/L2Projection.hpp"
#include "coupling/scheme/TimeInterpolation.hpp"
#include "structure/run/Simulation.hpp"
#include "structure/scene/Scene.hpp"

using namespace fsi;
using namespace fsi::coupling;

namespace {

const std::string kDrum = test::drumScene(R"(effects:
  mass_damping: {alpha: 50}
coupling: {interface: sheet}
time: {end: 1.0}
)");

StructureParticipant drum(const ParticipantOptions& options = {}) {
  return StructureParticipant(structure::loadSceneFromString(kDrum, "drum.yaml"), options);
}

ParticipantOptions minSubcycles(int n) {
  ParticipantOptions o;
  o.minSubcycles = n;
  return o;
}

}  // namespace

TEST(StructureParticipant, UniformInterfacePressureMatchesTheFollowerPressureEffect) {
  StructureParticipant s = drum();
  const int n = s.numInterfaceNodes();
  ASSERT_EQ(n, 9 * 9 + 8 * 8);
  const std::vector<double> p(n, 200.0);
  for (int k = 0; k < 100; ++k) {  // 0.1 s in fluid steps of 1 ms
    s.setPressure(p, p);
    s.advance(1e-3);
  }
  // The same load through the scene's own uniform follower pressure.
  structure::Scene ref = structure::loadSceneFromString(
      kDrum, "drum.yaml", {"effects.pressure={triangles: sheet, value: 200}", "time.end=0.1"});
  structure::RunOptions opt;
  opt.outDir = std::string(FSI_BINARY_DIR) + "/test-output/participant-ref-" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name();
  opt.quiet = true;
  structure::runSimulation(ref, opt);
  const auto u = s.interfaceDisplacement();
  const auto& N = ref.model->nodes;
  const auto& nodes = ref.couplingInterface->nodes;
  double maxDiff = 0, maxU = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    maxDiff = std::max(maxDiff, std::abs(u[3 * i + 2] - (N.x[3 * nodes[i] + 2] - N.X[3 * nodes[i] + 2])));
    maxU = std::max(maxU, std::abs(u[3 * i + 2]));
  }
  EXPECT_GT(maxU, 1e-3);
  // Same physics, steps cut at different instants (the coupled run lands on every millisecond).
  EXPECT_LT(maxDiff, 1e-3 * maxU);
}

TEST(StructureParticipant, InterfaceForceIsPressureTimesProjectedArea) {
  StructureParticipant s = drum();
  const std::vector<double> p(s.numInterfaceNodes(), 300.0);
  s.setPressure(p, p);
  s.advance(2e-3);
  const auto F = s.interfaceForce();
  // Any shape spanning the fixed unit-square rim has a projected area of 1 m².
  EXPECT_NEAR(F[2], 300.0, 1e-9 * 300.0);
}

TEST(StructureParticipant, CheckpointRestoreRepeatsAStepExactly) {
  StructureParticipant s = drum();
  const std::vector<double> p0(s.numInterfaceNodes(), 100.0), p1(s.numInterfaceNodes(), 150.0);
  s.setPressure(p0, p0);
  s.advance(2e-3);
  s.saveCheckpoint();
  s.setPressure(p0, p1);
  s.advance(1e-3);
  const auto first = s.interfaceDisplacement();
  const double t = s.time();
  s.restoreCheckpoint();
  s.setPressure(p0, p1);
  s.advance(1e-3);
  EXPECT_EQ(s.time(), t);
  EXPECT_EQ(s.interfaceDisplacement(), first);  // bitwise
}

TEST(StructureParticipant, SubcyclingCountFollowsTheStableStep) {
  StructureParticipant s = drum();
  const int n1 = s.subcyclesFor(1e-3), n2 = s.subcyclesFor(2e-3);
  EXPECT_GE(n1, 2);
  EXPECT_NEAR(double(n2) / n1, 2.0, 0.5);
  const long before = s.structuralSteps();
  s.advance(1e-3);
  EXPECT_NEAR(double(s.structuralSteps() - before), n1, 1.0);
}

TEST(StructureParticipant, PressureFromANonMatchingFluidMeshKeepsTheTotalForce) {
  // Kalro–Tezduyar's check: the force integrated on the fluid side equals the force on the structure side.
  // Fluid side: a finer quad mesh of the same unit square (13 x 11 quads) carrying p = 200 + 50 x + 30 y.
  StructureParticipant s = drum();
  InterfaceMesh fluid;
  const int nx = 13, ny = 11;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) fluid.points.push_back({-0.5 + double(i) / nx, -0.5 + double(j) / ny, 0.0});
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i;
      fluid.addFace({a, a + 1, a + nx + 2, a + nx + 1});
    }
  std::vector<double> pf(fluid.points.size());
  for (std::size_t k = 0; k < pf.size(); ++k)
    pf[k] = 200.0 + 50.0 * fluid.points[k][0] + 30.0 * fluid.points[k][1];
  const L2Projection toStructure(fluid, s.interfaceMesh());
  std::vector<double> ps(s.numInterfaceNodes());
  toStructure.apply(pf.data(), ps.data());
  // Linear fields are reproduced exactly, so the structure sees the same pressure...
  for (int k = 0; k < s.numInterfaceNodes(); ++k) {
    const auto& x = s.interfaceMesh().points[k];
    ASSERT_NEAR(ps[k], 200.0 + 50.0 * x[0] + 30.0 * x[1], 1e-10);
  }
  // ...and carries the same total force: ∫ p dA over the unit square = 200 N.
  s.setPressure(ps, ps);
  const auto F = s.interfaceForce();
  EXPECT_NEAR(F[2], 200.0, 1e-9);
  EXPECT_NEAR(F[0], 0.0, 1e-9);
  EXPECT_NEAR(F[1], 0.0, 1e-9);
}

TEST(StructureParticipant, NodalForcesAreAppliedAsGivenWithTheWindowRule) {
  StructureParticipant s = drum();
  const int n = s.numInterfaceNodes();
  // Start and end forces of a window; the default rule holds their mean over the window.
  std::vector<double> f0(3 * n), f1(3 * n);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      f0[3 * i + k] = 0.1 * (k + 1) + 0.01 * i;
      f1[3 * i + k] = 0.3 * (k + 1) - 0.02 * i;
    }
  s.setForces(f0, f1);
  s.advance(1e-3);
  const auto F = s.interfaceForce();
  for (int k = 0; k < 3; ++k) {
    double expected = 0;
    for (int i = 0; i < n; ++i) expected += 0.5 * (f0[3 * i + k] + f1[3 * i + k]);
    EXPECT_NEAR(F[k], expected, 1e-12 * std::abs(expected)) << "component " << k;
  }
  // Through the StructureSolver interface the loads are of the kind set last (forces, by setForces).
  Eigen::VectorXd a = Eigen::Map<Eigen::VectorXd>(f0.data(), 3 * n), b = a;
  s.solve(s.time(), 1e-3, a, b);
  const auto G = s.interfaceForce();
  for (int k = 0; k < 3; ++k) {
    double expected = 0;
    for (int i = 0; i < n; ++i) expected += f0[3 * i + k];
    EXPECT_NEAR(G[k], expected, 1e-12 * std::abs(expected));
  }
}

TEST(StructureParticipant, MinimumSubcyclesAreTakenAndRestartStateRoundTrips) {
  StructureParticipant s = drum(minSubcycles(7));
  const std::vector<double> p(s.numInterfaceNodes(), 200.0);
  EXPECT_GE(s.subcyclesFor(1e-3), 7);
  const long before = s.structuralSteps();
  s.setPressure(p, p);
  s.advance(1e-3);
  EXPECT_EQ(s.structuralSteps() - before, std::max(7, s.subcyclesFor(1e-3)));
  const std::string file = std::string(FSI_BINARY_DIR) + "/test-output/participant-state-" +
                           ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".h5";
  s.writeState(file, {{"extra", {1.0, 2.0}}});
  StructureParticipant t = drum(minSubcycles(7));
  const auto arrays = t.readState(file);
  EXPECT_EQ(arrays.at("extra"), (std::vector<double>{1.0, 2.0}));
  EXPECT_DOUBLE_EQ(t.time(), s.time());
  EXPECT_EQ(t.interfaceDisplacement(), s.interfaceDisplacement());
  // The energy ledger is part of the state: every field continues, so the exact bookkeeping (balance at
  // round-off) and the instability measures go on as in the run that was not stopped.
  EXPECT_EQ(t.integrator().energy().values(), s.integrator().energy().values());
  EXPECT_GT(s.integrator().energy().externalWork, 0.0);
  t.setPressure(p, p);
  s.advance(1e-3);
  t.advance(1e-3);
  EXPECT_EQ(t.interfaceDisplacement(), s.interfaceDisplacement());
  EXPECT_EQ(t.integrator().energy().values(), s.integrator().energy().values());
  EXPECT_LT(t.integrator().energy().balanceError(), 1e-12);
}

TEST(StructureParticipant, ThreeValuesPerNodeAreRefusedAsPressureNotReadAsForces) {
  // The kind of the loads is stated, never guessed from their number: a pressure vector three times the
  // interface's length (e.g. sampled on another mesh) was silently applied as nodal forces.
  StructureParticipant s = drum();
  const int n = s.numInterfaceNodes();
  const Eigen::VectorXd p = Eigen::VectorXd::Constant(3 * n, 100.0);
  EXPECT_THROW(s.solve(s.time(), 1e-3, p, p), std::invalid_argument);
  EXPECT_EQ(s.time(), 0.0);
  EXPECT_EQ(s.structuralSteps(), 0);
}

TEST(StructureParticipant, LoadKindIsExplicitAndEachKindChecksItsLength) {
  EXPECT_EQ(drum().loadKind(), structure::InterfaceLoadKind::Pressure);
  ParticipantOptions forces;
  forces.loadKind = structure::InterfaceLoadKind::NodalForces;
  StructureParticipant s = drum(forces);
  const int n = s.numInterfaceNodes();
  EXPECT_EQ(s.loadKind(), structure::InterfaceLoadKind::NodalForces);
  // One value per node is no force vector: refused, naming the kind and both counts.
  const Eigen::VectorXd perNode = Eigen::VectorXd::Constant(n, 1.0);
  try {
    s.solve(0.0, 1e-3, perNode, perNode);
    ADD_FAILURE() << "nodal forces of one value per node were accepted";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("nodal forces"), std::string::npos) << what;
    EXPECT_NE(what.find(std::to_string(3 * n)), std::string::npos) << what;
  }
  // Three per node: forces, summed as given (z only here).
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * n);
  for (int i = 0; i < n; ++i) f[3 * i + 2] = 0.5;
  s.solve(0.0, 1e-3, f, f);
  EXPECT_NEAR(s.interfaceForce()[2], 0.5 * n, 1e-12 * n);
  // Made for pressure: a pressure vector reads as one.
  StructureParticipant q = drum();
  EXPECT_EQ(q.interfaceForce()[2], 0.0);
  q.solve(q.time(), 1e-3, 300.0 * perNode, 300.0 * perNode);
  EXPECT_NEAR(q.interfaceForce()[2], 300.0, 1e-9 * 300.0);  // over the unit square's projected area
  // Subcycles below one are refused when the participant is made.
  EXPECT_THROW(drum(minSubcycles(0)), std::invalid_argument);
}

TEST(StructureParticipant, LinearWindowLoadIsTheCouplingLibrarysInterpolationPerSubstep) {
  // With `load_in_window: linear` each structural step of the window sees TimeInterpolation's value at its
  // start; the same window driven substep by substep with those loads held gives the same state.
  const std::string linear = test::drumScene(R"(coupling: {interface: sheet, load_in_window: linear}
time: {end: 1.0}
)");
  StructureParticipant s(structure::loadSceneFromString(linear, "drum.yaml"));
  StructureParticipant r(structure::loadSceneFromString(linear, "drum.yaml"));
  const int n = s.numInterfaceNodes(), m = s.subcyclesFor(2e-3);
  ASSERT_GE(m, 3);
  const std::vector<double> p0(n, 100.0), p1(n, 400.0);
  s.setPressure(p0, p1);
  s.advance(2e-3);
  EXPECT_EQ(s.structuralSteps(), m);
  const Eigen::VectorXd a = Eigen::VectorXd::Constant(n, 100.0), b = Eigen::VectorXd::Constant(n, 400.0);
  const TimeInterpolation loads(LoadInterpolation::Linear, a, b);
  for (int i = 0; i < m; ++i) {
    const Eigen::VectorXd q = loads.at(double(i) / m);
    const std::vector<double> held(q.data(), q.data() + q.size());
    r.setPressure(held, held);  // `linear` with equal ends: the value itself
    r.advanceTo(i + 1 == m ? 2e-3 : (i + 1) * (2e-3 / m));
  }
  EXPECT_EQ(r.structuralSteps(), m);
  const auto us = s.interfaceDisplacement(), ur = r.interfaceDisplacement();
  double diff = 0, size = 0;
  for (std::size_t k = 0; k < us.size(); ++k) {
    diff = std::max(diff, std::abs(us[k] - ur[k]));
    size = std::max(size, std::abs(us[k]));
  }
  EXPECT_GT(size, 0.0);
  EXPECT_LE(diff, 1e-12 * size);
}
