#pragma once
// The added-mass drum: the real structural solver (the drum film of TestScenes.hpp as a StructureParticipant,
// normal motion only) in a coupled loop with a reduced fluid, p = p_ext − m_a·ẅ (m_a: added mass per area),
// and its independent reference: the same membrane run alone with its areal mass increased by m_a — the
// monolithic equivalent of the added mass, exact because the nodes move only along the normal. Used by
// tests/unit/test_coupled_membrane.cpp and by the accuracy-versus-cost driver tests/cost/coupling_cost.cpp.
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "TestScenes.hpp"
#include "coupling/StructureParticipant.hpp"
#include "coupling/scheme/CouplingScheme.hpp"
#include "structure/run/Simulation.hpp"
#include "structure/scene/Scene.hpp"

namespace fsi::test {

inline const std::string& addedMassDrumScene() {
  static const std::string scene =
      drumScene(R"(  - {nodes: sheet, fix: [x, y]}   # normal motion only: the added mass acts on it alone
coupling: {interface: sheet}
time: {end: 1.0}
)");
  return scene;
}

constexpr double kDrumPext = 200.0;  // Pa

// Incompressible fluid reduced to its added mass on the normal motion; acceleration from the interface
// displacement history by second differences (the fluid's own time discretisation).
class AddedMassFluid final : public coupling::FluidSolver {
 public:
  AddedMassFluid(int nodes, double addedMass, double t0, double pressure = kDrumPext)
      : n_(nodes), ma_(addedMass), pext_(pressure), tWindow_(t0) {
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
      p[i] = pext_ - ma_ * a;
    }
    return p;
  }
  void saveCheckpoint() override {}
  void restoreCheckpoint() override {}

 private:
  int n_;
  double ma_, pext_, tWindow_;
  Eigen::VectorXd wPrev_, wCur_, last_;
};

struct DrumRun {
  bool finite = true;
  double centre = 0;  // centre displacement at the end
  double meanIterations = 0;
  int windows = 0;
  long structuralSteps = 0;
  double wallSeconds = 0;  // the coupling loop only
  int notConverged = 0;    // windows accepted without convergence
  int firstWindowIterations = 0;
  bool firstWindowConverged = false;
  std::string diagnosis;  // what the structure said when it stopped on a non-finite state
};

struct DrumSettings {
  coupling::SchemeKind kind = coupling::SchemeKind::Implicit;
  double addedMass = 5.0;  // kg/m², against the film's 1 kg/m²
  double window = 0.25e-3;
  int windows = 320;
  double relativeTolerance = 1e-8;
  int maxIterations = 100;
  int minSubcycles = 1;
  double pressure = kDrumPext;  // p_ext, applied from t = 0 [Pa]
};

/// The coupled run; `acceleration` for the implicit scheme (null for the staggered one).
inline DrumRun runAddedMassDrum(const DrumSettings& c, std::unique_ptr<coupling::Acceleration> acceleration) {
  using namespace fsi::coupling;
  ParticipantOptions options;
  options.minSubcycles = c.minSubcycles;
  StructureParticipant s(structure::loadSceneFromString(addedMassDrumScene(), "drum.yaml"), options);
  AddedMassFluid fluid(s.numInterfaceNodes(), c.addedMass, 0.0, c.pressure);
  CouplingConfig cfg;
  cfg.kind = c.kind;
  cfg.timeWindowSize = c.window;
  cfg.endTime = c.windows * c.window;
  cfg.relativeTolerance = c.relativeTolerance;
  cfg.maxIterations = c.maxIterations;
  CouplingScheme scheme(cfg, s, std::move(acceleration));
  const Eigen::VectorXd p0 = Eigen::VectorXd::Constant(s.numInterfaceNodes(), c.pressure);
  scheme.initialize(0.0, Eigen::VectorXd::Zero(3 * s.numInterfaceNodes()), p0);
  DrumRun r;
  int centre = 0;
  double best = 1e9;
  for (int i = 0; i < s.numInterfaceNodes(); ++i) {
    const auto& x = s.interfaceMesh().points[std::size_t(i)];
    if (x[0] * x[0] + x[1] * x[1] < best) best = x[0] * x[0] + x[1] * x[1], centre = i;
  }
  const auto t0 = std::chrono::steady_clock::now();
  while (scheme.isCouplingOngoing()) {
    try {
      const WindowReport w = runTimeWindow(scheme, fluid);
      if (w.window == 0) r.firstWindowIterations = w.iterations, r.firstWindowConverged = w.converged;
    } catch (const std::runtime_error& e) {  // the structure stopped on a non-finite state: unstable
      r.finite = false;
      r.diagnosis = e.what();
      break;
    }
    const double w = scheme.acceptedDisplacement()[3 * centre + 2];
    if (!std::isfinite(w) || std::abs(w) > 10.0) {
      r.finite = false;
      break;
    }
  }
  r.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.windows = scheme.statistics().windows;
  r.structuralSteps = s.structuralSteps();
  r.notConverged = scheme.statistics().notConverged;
  if (!r.finite) return r;
  r.centre = scheme.acceptedDisplacement()[3 * centre + 2];
  r.meanIterations = scheme.statistics().meanIterations();
  return r;
}

/// The monolithic equivalent: the film alone with areal mass ρt + m_a, to tEnd; its centre displacement.
/// `outDir`: where the run writes its results (one folder per caller: tests run in parallel processes).
inline double addedMassDrumMonolithic(double addedMass, double tEnd, const std::string& outDir,
                                      double safety = 0.9, double pressure = kDrumPext) {
  // Areal mass ρt + m_a through the density: (1000·1e-3 + m_a)/1e-3.
  const double rho = (1.0 + addedMass) / 1e-3;
  structure::Scene sc = structure::loadSceneFromString(
      addedMassDrumScene(), "drum.yaml",
      {"materials.film.density=" + std::to_string(rho),
       "effects={pressure: {triangles: sheet, value: " + std::to_string(pressure) + "}}",
       "time.end=" + std::to_string(tEnd), "time.safety=" + std::to_string(safety)});
  structure::RunOptions opt;
  opt.outDir = outDir;
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

}  // namespace fsi::test
