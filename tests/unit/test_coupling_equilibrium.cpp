// Coupling to equilibrium (coupling/scheme/Equilibrium, CouplingConfig::loadRelaxation; docs/COUPLING.md
// "Coupling to equilibrium"):
//  * a string under an air cushion: the cushion's pressure drops with the volume the string displaces,
//    p = p0 - kappa V, so the load depends on the displacement. Its static equilibrium is known in closed
//    form (below). Equilibrium windows reach it in far fewer windows than time-accurate ones;
//  * with a strong feedback (kappa c = 3) the window-to-window map of equilibrium windows has the factor
//    -kappa c: it diverges with the fluid's load handed over unchanged, and load relaxation converges for
//    omega < 2 / (1 + kappa c), the bound of that linear map;
//  * the real explicit structure (StructureParticipant, the drum film) in equilibrium mode: static residual,
//    window velocity and energy balance;
//  * the scheme relaxes the load towards the previous window's applied load, never towards an iterate.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "TestScenes.hpp"
#include "coupling/StructureParticipant.hpp"
#include "coupling/scheme/CouplingScheme.hpp"
#include "coupling/scheme/Equilibrium.hpp"
#include "coupling/scheme/Subcycling.hpp"
#include "coupling/scheme/acceleration/Aitken.hpp"
#include "coupling/scheme/acceleration/IqnIls.hpp"
#include "structure/scene/Scene.hpp"

using namespace fsi::coupling;
using Eigen::VectorXd;

namespace {

// A taut string of unit length, tension T and line density rho, fixed at both ends, n free nodes at spacing
// h = 1 / (n + 1), lumped mass rho h, integrated by central differences (leapfrog) with mass damping alpha.
// The interface is the n nodes' transverse displacements; loads are nodal forces.
class String final : public StructureStepper, public RelaxationStepper {
 public:
  String(int n, double alpha) : n_(n), h_(1.0 / (n + 1)), alpha_(alpha), x_(VectorXd::Zero(n)), v_(x_) {}

  // Central differences are stable for dt <= 2 / omega_max, omega_max^2 <= 4 T / (rho h^2): 90 % of that.
  double stableTimeStep() const override { return 0.9 * h_ * std::sqrt(kRho / kT); }
  void step(double, double dt, const VectorXd&, const VectorXd& f1) override { leapfrog(dt, f1); }
  VectorXd interfaceDisplacement() const override { return x_; }
  void saveCheckpoint() override { saved_ = {x_, v_}; }
  void restoreCheckpoint() override { x_ = saved_.first, v_ = saved_.second; }

  void freezeLoads(const VectorXd& f) override { frozen_ = f; }
  double relaxStep() override {
    leapfrog(stableTimeStep(), frozen_);
    return 0.5 * kRho * h_ * v_.squaredNorm();
  }
  void stopMotion() override {
    v_.setZero();
    fresh_ = true;
  }
  void endWindow(double, const VectorXd& velocity) override { windowVelocity = velocity; }

  // K x: the tension's restoring force.
  VectorXd stiffness(const VectorXd& x) const {
    VectorXd k(n_);
    for (int i = 0; i < n_; ++i)
      k[i] = kT / h_ * (2.0 * x[i] - (i > 0 ? x[i - 1] : 0.0) - (i + 1 < n_ ? x[i + 1] : 0.0));
    return k;
  }
  VectorXd windowVelocity;
  static constexpr double kT = 1.0, kRho = 1.0;

 private:
  // From rest (a start or a kinetic-damping stop) the first kick is half a step's, as CentralDifference's.
  void leapfrog(double dt, const VectorXd& f) {
    const double m = kRho * h_, kick = fresh_ ? 0.5 * dt : dt;
    v_ = ((1.0 - 0.5 * alpha_ * kick) * v_ + kick / m * (f - stiffness(x_))) / (1.0 + 0.5 * alpha_ * kick);
    x_ += dt * v_;
    fresh_ = false;
  }
  int n_;
  double h_, alpha_;
  VectorXd x_, v_, frozen_;
  bool fresh_ = true;  // at rest: the next kick is half a step's
  std::pair<VectorXd, VectorXd> saved_;
};

// The air cushion under the string: nodal forces h (p0 - kappa V), V = h sum(x) the displaced volume; with
// mu > 0 also the added mass of a fluid, mu times the string's nodal mass, reacting to the interface
// acceleration the fluid derives from the displacements it is given (BDF2, like an ALE solver).
class Cushion final : public FluidSolver {
 public:
  Cushion(int n, double p0, double kappa, double mu = 0.0, double dt = 1.0)
      : h_(1.0 / (n + 1)), p0_(p0), kappa_(kappa), ma_(mu * String::kRho * h_), dt_(dt), n_(n) {
    s_ = {VectorXd::Zero(n), VectorXd::Zero(n), VectorXd::Zero(n), VectorXd::Zero(n), 0};
  }
  VectorXd solve(double, double, const VectorXd& d) override {
    VectorXd w, b;
    if (s_.steps == 0) {  // BDF1 start
      w = (d - s_.x) / dt_;
      b = (w - s_.u) / dt_;
    } else {
      w = (3.0 * d - 4.0 * s_.x + s_.xm1) / (2.0 * dt_);
      b = (3.0 * w - 4.0 * s_.u + s_.um1) / (2.0 * dt_);
    }
    s_ = {d, s_.x, w, s_.u, s_.steps + 1};
    return loads(d) - ma_ * b;
  }
  VectorXd loads(const VectorXd& d) const {
    return VectorXd::Constant(n_, h_ * (p0_ - kappa_ * h_ * d.sum()));
  }
  void saveCheckpoint() override { saved_ = s_; }
  void restoreCheckpoint() override { s_ = saved_; }

 private:
  struct State {
    VectorXd x, xm1, u, um1;
    int steps;
  };
  double h_, p0_, kappa_, ma_, dt_;
  int n_;
  State s_, saved_;
};

// Static equilibrium in closed form. Under a uniform load q per unit length the discrete string's nodes lie
// on the parabola x(1 - x) q / (2T) exactly (its second difference is constant), so with q = p, x = p u,
// u_i = x_i (1 - x_i) / (2T), and the volume V = p c, c = h sum(u_i). The cushion's p = p0 - kappa V then
// gives p = p0 / (1 + kappa c).
struct Exact {
  VectorXd d;
  double c = 0;
};
Exact exactEquilibrium(int n, double p0, double kappa) {
  const double h = 1.0 / (n + 1);
  VectorXd u(n);
  for (int i = 0; i < n; ++i) {
    const double x = (i + 1) * h;
    u[i] = x * (1.0 - x) / (2.0 * String::kT);
  }
  Exact e;
  e.c = h * u.sum();
  e.d = p0 / (1.0 + kappa * e.c) * u;
  return e;
}

constexpr int kNodes = 15;
constexpr double kP0 = 1.0;
constexpr double kWindow = 0.05;  // 1/40 of the string's fundamental period 2 sqrt(rho / T)

struct CushionRun {
  std::vector<double> error;  // |d_k - d*|_inf / |d*|_inf after window k (error[0]: the flat start)
  int settled = -1;           // first window from which the error stays <= kSettled
  VectorXd lastVelocity;      // the string's window velocity (equilibrium mode)
  VectorXd lastStep;          // d_k - d_{k-1} of the last window
};
constexpr double kSettled = 1e-4;

struct CushionSetup {
  double alpha = 0.0;  // the string's mass damping
  double mu = 0.0;     // added mass over the string's mass
  bool implicit = false;
  EquilibriumOptions relaxation{};  // equilibrium mode: pseudo-steps per window, start from rest or carried
};

CushionRun runCushion(StructureMode mode, double kappa, double omega, int windows,
                      const CushionSetup& c = {}) {
  String string(kNodes, c.alpha);
  SubcycledStructure subcycled(string);
  EquilibriumStructure relaxed(string, c.relaxation);  // 100 pseudo-steps per window unless set
  StructureSolver& structure =
      mode == StructureMode::Equilibrium ? static_cast<StructureSolver&>(relaxed) : subcycled;
  Cushion cushion(kNodes, kP0, kappa, c.mu, kWindow);
  const Exact exact = exactEquilibrium(kNodes, kP0, kappa);
  CouplingConfig cfg;
  cfg.kind = c.implicit ? SchemeKind::Implicit : SchemeKind::Staggered;
  cfg.timeWindowSize = kWindow;
  cfg.endTime = windows * kWindow;
  cfg.extrapolationOrder = 0;
  cfg.loadRelaxation = omega;
  cfg.relativeTolerance = 1e-8;
  cfg.maxIterations = 100;
  CouplingScheme scheme(cfg, structure, c.implicit ? std::make_unique<IqnIls>(IqnIlsOptions{}) : nullptr);
  const VectorXd zero = VectorXd::Zero(kNodes);
  scheme.initialize(0.0, zero, cushion.loads(zero));
  CushionRun r;
  const double scale = exact.d.lpNorm<Eigen::Infinity>();
  r.error.push_back(1.0);
  VectorXd previous = zero;
  while (scheme.isCouplingOngoing()) {
    runTimeWindow(scheme, cushion);
    const VectorXd& d = scheme.acceptedDisplacement();
    r.lastStep = d - previous;
    previous = d;
    const double e = (d - exact.d).lpNorm<Eigen::Infinity>() / scale;
    r.error.push_back(std::isfinite(e) ? e : INFINITY);
    if (!(e <= kSettled))
      r.settled = -1;
    else if (r.settled < 0)
      r.settled = int(r.error.size()) - 1;
    if (!(e < 1e6)) break;  // diverged
  }
  r.lastVelocity = string.windowVelocity;
  return r;
}

}  // namespace

TEST(CouplingEquilibrium, ClosedFormEquilibriumOfTheCushionedString) {
  // The reference itself: K d* = h (p0 - kappa h sum d*) at every node.
  for (const double kappa : {0.0, 12.0, 72.0}) {
    const Exact e = exactEquilibrium(kNodes, kP0, kappa);
    String s(kNodes, 0.0);
    const Cushion c(kNodes, kP0, kappa);
    EXPECT_LT((s.stiffness(e.d) - c.loads(e.d)).lpNorm<Eigen::Infinity>(), 1e-14) << kappa;
  }
}

TEST(CouplingEquilibrium, EquilibriumWindowsSettleInFarFewerWindowsThanTimeAccurateOnes) {
  // A mild feedback, kappa c = 0.5 (c = 1/12 - h^2/12 for the string: kappa = 6 / (1 - h^2)).
  const double h = 1.0 / (kNodes + 1), kappa = 6.0 / (1.0 - h * h);
  ASSERT_NEAR(kappa * exactEquilibrium(kNodes, kP0, kappa).c, 0.5, 1e-12);
  const CushionRun eq = runCushion(StructureMode::Equilibrium, kappa, 1.0, 200);
  // Time-accurate windows need physical damping to settle at all: 5 % of critical on the fundamental
  // (alpha = 2 zeta omega_1, omega_1 = pi sqrt(T / rho) without the cushion). Undamped they never settle.
  const double alpha = 2.0 * 0.05 * M_PI;
  CushionSetup damped;
  damped.alpha = alpha;
  const CushionRun ta = runCushion(StructureMode::TimeAccurate, kappa, 1.0, 4000, damped);
  const CushionRun undamped = runCushion(StructureMode::TimeAccurate, kappa, 1.0, 4000);
  std::printf(
      "kappa c 0.5: settled to %g after %d equilibrium windows, %d time-accurate windows (5 %% damping),"
      " undamped error after 4000 windows %.3g\n",
      kSettled, eq.settled, ta.settled, undamped.error.back());
  ASSERT_GT(eq.settled, 0);
  ASSERT_GT(ta.settled, 0);
  // Both reach the closed-form equilibrium; the equilibrium windows in a tenth of the windows at most.
  EXPECT_LE(10 * eq.settled, ta.settled);
  EXPECT_LT(eq.error.back(), kSettled);
  EXPECT_LT(ta.error.back(), kSettled);
  EXPECT_LT(undamped.settled, 0);
  // The velocity handed over is the window's displacement change over its length.
  EXPECT_LT((eq.lastVelocity - eq.lastStep / kWindow).norm(), 1e-12 * (1.0 + eq.lastVelocity.norm()));
}

TEST(CouplingEquilibrium, CarriedPseudoMotionConvergesWhatTooFewStepsFromRestOnlyCreepTowards) {
  // One pseudo-step per window spans 0.056 s of the string's pseudo-time, 1/36 of its fundamental period (2
  // s): from rest, a window moves the fundamental by ~(omega h)^2 / 2 = 1.5 % of the way, and it creeps (as
  // the canopy's swing on its lines does in the coupled ram-air run, docs/RAMAIR.md). Carried over, the
  // motion builds up across windows, and the kinetic damping still stops it at every peak, a peak between
  // two windows included. Both must reach the closed form; carried in half the windows at most (measured:
  // 97 against 395).
  const double h = 1.0 / (kNodes + 1), kappa = 6.0 / (1.0 - h * h);  // kappa c = 0.5, as above
  CushionSetup rest, carry;
  rest.relaxation = {1, EquilibriumStart::Rest};
  carry.relaxation = {1, EquilibriumStart::Carry};
  const CushionRun r = runCushion(StructureMode::Equilibrium, kappa, 1.0, 3000, rest);
  const CushionRun c = runCushion(StructureMode::Equilibrium, kappa, 1.0, 3000, carry);
  std::printf("1 pseudo-step per window: settled to %g after %d windows from rest, %d carried\n", kSettled,
              r.settled, c.settled);
  ASSERT_GT(r.settled, 0);
  ASSERT_GT(c.settled, 0);
  EXPECT_LE(2 * c.settled, r.settled);
  EXPECT_LT(c.error.back(), kSettled);
  // The window velocity stays the displacement change over the window, whatever the pseudo-velocities.
  EXPECT_LT((c.lastVelocity - c.lastStep / kWindow).norm(), 1e-12 * (1.0 + c.lastVelocity.norm()));
}

TEST(CouplingEquilibrium, CarryFromRelaxesFromRestUntilItsTimeThenCarries) {
  // The set-up above with the carrying from window 100's end on: the windows up to there are the run from
  // rest to the last bit (the same arithmetic), the ones after differ, and the carried motion then settles
  // long before the run from rest does (measured: from rest 395 windows, carried from the start 97).
  const double h = 1.0 / (kNodes + 1), kappa = 6.0 / (1.0 - h * h);
  CushionSetup rest, late;
  rest.relaxation = {1, EquilibriumStart::Rest};
  late.relaxation = {1, EquilibriumStart::Carry, 100 * kWindow};
  const CushionRun r = runCushion(StructureMode::Equilibrium, kappa, 1.0, 3000, rest);
  const CushionRun l = runCushion(StructureMode::Equilibrium, kappa, 1.0, 3000, late);
  std::printf("1 pseudo-step per window: settled after %d windows from rest, %d carried from window 100\n",
              r.settled, l.settled);
  // error[k]: after window k; window 101 starts at 100 windows' time and is the first carried one. It starts
  // at rest too (window 100 ended at rest) but keeps its motion: window 102 is the first that differs.
  ASSERT_GT(l.error.size(), 103u);
  for (std::size_t k = 0; k <= 101; ++k) EXPECT_EQ(l.error[k], r.error[k]) << "window " << k;
  EXPECT_NE(l.error[102], r.error[102]);
  ASSERT_GT(r.settled, 0);
  ASSERT_GT(l.settled, 100);
  EXPECT_LT(l.settled, r.settled - 100);
  EXPECT_LT(l.error.back(), kSettled);
}

TEST(CouplingEquilibrium, LoadRelaxationConvergesAStrongFeedbackThatDivergesWithout) {
  // kappa c = 3: a fully relaxed structure answers the load p with the volume c p, so from window to window
  // p_{k+1} - p* = (1 - omega (1 + kappa c)) (p_k - p*): factor -3 at omega = 1 (the shape oscillates with
  // growing amplitude), convergent for omega < 2 / (1 + kappa c) = 0.5, best at omega = 1 / (1 + kappa c).
  const double h = 1.0 / (kNodes + 1), kappa = 36.0 / (1.0 - h * h);
  ASSERT_NEAR(kappa * exactEquilibrium(kNodes, kP0, kappa).c, 3.0, 1e-12);
  auto run = [&](double omega) {
    const CushionRun r = runCushion(StructureMode::Equilibrium, kappa, omega, 60);
    std::printf("kappa c 3, omega %.2f: error after windows 1..6:", omega);
    for (std::size_t k = 1; k <= 6 && k < r.error.size(); ++k) std::printf(" %.3g", r.error[k]);
    std::printf(", last (window %zu) %.3g, settled at window %d\n", r.error.size() - 1, r.error.back(),
                r.settled);
    return r;
  };
  const CushionRun off = run(1.0), over = run(0.6), safe = run(0.4), best = run(0.25);
  // The measured window-to-window factor is that of the linear map (the structure nearly relaxes in each
  // window): |1 - omega (1 + kappa c)| = 3, 1.4 and 0.6, within 10 %.
  auto rate = [](const CushionRun& r, std::size_t a, std::size_t b) {
    return std::pow(r.error[b] / r.error[a], 1.0 / double(b - a));
  };
  std::printf("factors: omega 1 %.3f, omega 0.6 %.3f, omega 0.4 %.3f\n", rate(off, 2, 10), rate(over, 5, 30),
              rate(safe, 3, 20));
  EXPECT_NEAR(rate(off, 2, 10), 3.0, 0.3);
  EXPECT_NEAR(rate(over, 5, 30), 1.4, 0.14);
  EXPECT_NEAR(rate(safe, 3, 20), 0.6, 0.06);
  // Without relaxation, and just beyond the bound, the error grows from window to window.
  EXPECT_GT(off.error.back(), 1e3);
  EXPECT_GT(over.error.back(), 1.0);
  // Inside the bound the closed-form equilibrium is reached; at the optimum within a few windows (only the
  // relaxation left inside each window keeps it from one).
  ASSERT_GT(safe.settled, 0);
  ASSERT_GT(best.settled, 0);
  EXPECT_LT(safe.error.back(), kSettled);
  EXPECT_LT(best.settled, safe.settled);
}

TEST(CouplingEquilibrium, SchemeRelaxesTowardsThePreviousWindowsAppliedLoad) {
  // A structure that records the end loads it gets and answers with a fixed displacement.
  struct Recorder final : StructureSolver {
    VectorXd solve(double, double, const VectorXd& f0, const VectorXd& f1) override {
      starts.push_back(f0[0]);
      ends.push_back(f1[0]);
      return VectorXd::Constant(1, 1.0);
    }
    void saveCheckpoint() override {}
    void restoreCheckpoint() override {}
    std::vector<double> starts, ends;
  } rec;
  CouplingConfig cfg;
  cfg.timeWindowSize = 1.0;
  cfg.endTime = 2.0;
  cfg.loadRelaxation = 0.25;
  cfg.maxIterations = 2;  // a second pass of each window: its load relaxes towards the same start
  cfg.relativeTolerance = 1e-12;
  CouplingScheme scheme(cfg, rec, std::make_unique<Aitken>());
  scheme.initialize(0.0, VectorXd::Zero(1), VectorXd::Constant(1, 8.0));
  scheme.advance(VectorXd::Constant(1, 4.0));   // window 0, pass 1
  scheme.advance(VectorXd::Constant(1, 0.0));   // window 0, pass 2: accepted
  scheme.advance(VectorXd::Constant(1, 16.0));  // window 1, pass 1
  ASSERT_EQ(rec.ends.size(), 3u);
  EXPECT_DOUBLE_EQ(rec.ends[0], 0.25 * 4.0 + 0.75 * 8.0);
  EXPECT_DOUBLE_EQ(rec.ends[1], 0.25 * 0.0 + 0.75 * 8.0);  // the start's load, not the first pass's
  EXPECT_DOUBLE_EQ(rec.starts[2], 6.0);                    // the accepted applied load
  EXPECT_DOUBLE_EQ(rec.ends[2], 0.25 * 16.0 + 0.75 * 6.0);
  EXPECT_DOUBLE_EQ(scheme.loadsAtWindowStart()[0], 6.0);
  for (const double w : {0.0, -0.5, 1.5, std::nan("")}) {
    CouplingConfig bad = cfg;
    bad.loadRelaxation = w;
    EXPECT_THROW(CouplingScheme(bad, rec, std::make_unique<Aitken>()), std::invalid_argument) << w;
  }
}

// ---------------------------------------------------------------------------------------------------------
// The product's structure: the drum film (1 m square membrane, clamped edges, no prestress) under 200 Pa of
// nodal forces held constant by the "fluid".

namespace {

const std::string kDrum = fsi::test::drumScene("coupling: {interface: sheet}\ntime: {end: 1.0}\n");

VectorXd pressureForces(const StructureParticipant& s, double p) {
  const InterfaceMesh& m = s.interfaceMesh();
  VectorXd f = VectorXd::Zero(3 * Eigen::Index(m.points.size()));
  for (std::size_t e = 0; e + 2 < m.faceNodes.size(); e += 3) {
    const auto& a = m.points[std::size_t(m.faceNodes[e])];
    const auto& b = m.points[std::size_t(m.faceNodes[e + 1])];
    const auto& c = m.points[std::size_t(m.faceNodes[e + 2])];
    const double area = 0.5 * std::abs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    for (int k = 0; k < 3; ++k) f(3 * Eigen::Index(m.faceNodes[e + std::size_t(k)]) + 2) += p * area / 3.0;
  }
  return f;
}

class ConstantLoad final : public FluidSolver {
 public:
  explicit ConstantLoad(VectorXd f) : f_(std::move(f)) {}
  VectorXd solve(double, double, const VectorXd&) override { return f_; }
  void saveCheckpoint() override {}
  void restoreCheckpoint() override {}

 private:
  VectorXd f_;
};

struct DrumRun {
  std::vector<double> residual;  // static residual ratio after each window
  int settled = -1;              // first window with residual ratio <= 1e-3 (the relaxation solver's default)
  double balance = 0;            // energy balance error at the end
  long steps = 0;                // structural steps
  std::vector<double> velocity, step;  // interface velocity and d_k - d_{k-1} of the last window
};

DrumRun runDrum(StructureMode mode, int windows, double window) {
  ParticipantOptions options;
  options.loadKind = fsi::structure::InterfaceLoadKind::NodalForces;
  options.mode = mode;
  StructureParticipant s(fsi::structure::loadSceneFromString(kDrum, "drum.yaml"), options);
  ConstantLoad fluid(pressureForces(s, 200.0));
  CouplingConfig cfg;
  cfg.kind = SchemeKind::Staggered;
  cfg.timeWindowSize = window;
  cfg.endTime = windows * window;
  CouplingScheme scheme(cfg, s);
  const VectorXd zero = VectorXd::Zero(3 * s.numInterfaceNodes());
  scheme.initialize(0.0, zero, fluid.solve(0, 0, zero));
  DrumRun r;
  VectorXd previous = zero;
  while (scheme.isCouplingOngoing()) {
    runTimeWindow(scheme, fluid);
    r.residual.push_back(s.staticResidualRatio());
    if (r.settled < 0 && r.residual.back() <= 1e-3) r.settled = int(r.residual.size());
    const VectorXd d = scheme.acceptedDisplacement();
    const VectorXd step = d - previous;
    previous = d;
    r.step.assign(step.data(), step.data() + step.size());
  }
  EXPECT_NEAR(s.time(), windows * window, 1e-9 * window);  // the clock ends on the fluid's time
  r.velocity = s.interfaceVelocity();
  r.balance = s.integrator().energy().balanceError();
  r.steps = s.structuralSteps();
  return r;
}

}  // namespace

TEST(CouplingEquilibriumFilm, ReachesStaticEquilibriumWhereTimeAccurateWindowsStillOscillate) {
  constexpr int kWindows = 60;
  constexpr double kDt = 1e-3;
  const DrumRun eq = runDrum(StructureMode::Equilibrium, kWindows, kDt);
  const DrumRun ta = runDrum(StructureMode::TimeAccurate, kWindows, kDt);
  std::printf(
      "drum, 200 Pa: equilibrium residual %.3g after %d windows (<= 1e-3 from window %d, %ld steps); "
      "time-accurate %.3g (%ld steps)\n",
      eq.residual.back(), kWindows, eq.settled, eq.steps, ta.residual.back(), ta.steps);
  ASSERT_GT(eq.settled, 0);
  // Equilibrium holds from there on: the residual does not come back.
  for (std::size_t k = std::size_t(eq.settled); k < eq.residual.size(); ++k)
    EXPECT_LE(eq.residual[k], 1e-3) << k;
  // The undamped film integrated in time is still far from equilibrium (it oscillates about it).
  EXPECT_GT(*std::max_element(ta.residual.end() - 10, ta.residual.end()), 0.05);
  EXPECT_EQ(eq.steps, 100L * kWindows);  // equilibriumSteps' default per window
  // Kinetic damping books the energy it removes: the balance stays at round-off.
  EXPECT_LT(eq.balance, 1e-9);
  ASSERT_EQ(eq.velocity.size(), eq.step.size());
  for (std::size_t i = 0; i < eq.step.size(); ++i) EXPECT_NEAR(eq.velocity[i], eq.step[i] / kDt, 1e-9) << i;
}

TEST(CouplingEquilibriumFilm, ModeAndStepsAreChecked) {
  const auto make = [](StructureMode mode, int steps) {
    ParticipantOptions options;
    options.loadKind = fsi::structure::InterfaceLoadKind::NodalForces;
    options.mode = mode;
    options.equilibrium.steps = steps;
    return StructureParticipant(fsi::structure::loadSceneFromString(kDrum, "drum.yaml"), options);
  };
  EXPECT_EQ(make(StructureMode::TimeAccurate, 100).structureMode(), StructureMode::TimeAccurate);
  EXPECT_THROW(make(StructureMode::Equilibrium, 0), std::invalid_argument);
  StructureParticipant s = make(StructureMode::Equilibrium, 7);
  EXPECT_EQ(s.structureMode(), StructureMode::Equilibrium);
  const long before = s.structuralSteps();
  s.solve(0.0, 1e-3, VectorXd::Zero(3 * s.numInterfaceNodes()), pressureForces(s, 100.0));
  EXPECT_EQ(s.structuralSteps() - before, 7);
  EXPECT_EQ(s.equilibriumReport().steps, 7);
}

TEST(CouplingEquilibrium, AnAddedMassMakesEquilibriumWindowsDivergeUnlessRelaxedOrIterated) {
  // The fluid's added mass makes the load depend on the displacement through the interface acceleration:
  // BDF2 gives d(load)/d(displacement) = (9/4) M_a / dt^2 per node, against the string's stiffness K_1 =
  // m omega_1^2 in its fundamental, a ratio (9/4) mu / (omega_1 dt)^2 = 0.91 at mu = 0.01 (omega_1 = pi,
  // dt = 0.05), on top of the cushion's kappa c = 0.5. Equilibrium windows answer the load statically, so
  // the window-to-window map has a factor beyond -1: it diverges. Load relaxation or the implicit scheme
  // settle it; a heavy added mass (mu = 1, ratio 91) settles with neither in 400 windows.
  const double h = 1.0 / (kNodes + 1), kappa = 6.0 / (1.0 - h * h);
  CushionSetup light, lightImplicit, heavy, heavyImplicit;
  light.mu = lightImplicit.mu = 0.01;
  heavy.mu = heavyImplicit.mu = 1.0;
  lightImplicit.implicit = heavyImplicit.implicit = true;
  auto run = [&](const char* what, double omega, const CushionSetup& c) {
    const CushionRun r = runCushion(StructureMode::Equilibrium, kappa, omega, 400, c);
    std::printf("%s, omega %g: error %.3g after %zu windows, settled at window %d\n", what, omega,
                r.error.back(), r.error.size() - 1, r.settled);
    return r;
  };
  EXPECT_GT(run("mu 0.01 staggered", 1.0, light).error.back(), 1e3);
  const CushionRun relaxed = run("mu 0.01 staggered", 0.1, light);
  EXPECT_LT(relaxed.error.back(), kSettled);
  EXPECT_GT(relaxed.settled, 0);
  const CushionRun iterated = run("mu 0.01 implicit IQN-ILS", 1.0, lightImplicit);
  EXPECT_LT(iterated.error.back(), kSettled);
  EXPECT_GT(iterated.settled, 0);
  EXPECT_GT(run("mu 1 staggered", 0.01, heavy).error.back(), 1e3);
  EXPECT_GT(run("mu 1 implicit IQN-ILS", 1.0, heavyImplicit).error.back(), 1e-2);
}

TEST(CouplingEquilibrium, ARestartKeepsTheRelaxedLoad) {
  // Ten equilibrium windows with omega = 0.4 (kappa c = 3), against five, a restart (a new scheme from the
  // structure's state, the displacement history and the load the structure got last), and five more.
  const double h = 1.0 / (kNodes + 1), kappa = 36.0 / (1.0 - h * h);
  Cushion cushion(kNodes, kP0, kappa);
  CouplingConfig cfg;
  cfg.kind = SchemeKind::Staggered;
  cfg.timeWindowSize = kWindow;
  cfg.extrapolationOrder = 0;
  cfg.loadRelaxation = 0.4;
  const VectorXd zero = VectorXd::Zero(kNodes);
  String a(kNodes, 0.0);
  EquilibriumStructure ea(a);
  cfg.endTime = 10 * kWindow;
  CouplingScheme full(cfg, ea);
  full.initialize(0.0, zero, cushion.loads(zero));
  String b(kNodes, 0.0);
  EquilibriumStructure eb(b);
  cfg.endTime = 5 * kWindow;
  CouplingScheme first(cfg, eb);
  first.initialize(0.0, zero, cushion.loads(zero));
  for (int k = 0; k < 5; ++k) {
    runTimeWindow(full, cushion);
    runTimeWindow(first, cushion);
  }
  auto resume = [&](bool withLoads) {
    String c = b;  // the structure's state at the restart
    EquilibriumStructure ec(c);
    CouplingConfig rc = cfg;
    rc.endTime = 10 * kWindow;
    CouplingScheme second(rc, ec);
    const VectorXd& d = first.acceptedDisplacement();
    second.initialize(first.time(), d, cushion.loads(d));
    second.restoreHistory(first.history());
    if (withLoads) second.restoreLoadsAtWindowStart(first.loadsAtWindowStart());
    while (second.isCouplingOngoing()) runTimeWindow(second, cushion);
    return VectorXd(second.acceptedDisplacement());
  };
  while (full.isCouplingOngoing()) runTimeWindow(full, cushion);
  const VectorXd& d = full.acceptedDisplacement();
  EXPECT_EQ((resume(true) - d).lpNorm<Eigen::Infinity>(), 0.0);
  // Restarting from the fluid's load instead changes the path (not the steady state).
  EXPECT_GT((resume(false) - d).lpNorm<Eigen::Infinity>(), 1e-3 * d.lpNorm<Eigen::Infinity>());
  EXPECT_THROW(full.restoreLoadsAtWindowStart(VectorXd::Zero(kNodes + 1)), CouplingError);
}
