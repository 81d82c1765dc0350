#pragma once
// Reduced coupling models with known answers, shared by the coupling-scheme tests
// (tests/unit/test_coupling_schemes.cpp) and the coupling hard cases (tests/unit/test_hard_coupling.cpp):
//  * a piston and a string under an incompressible fluid reduced to its added mass (Newmark structure,
//    Newmark or BDF2 fluid kinematics), with their monolithic solutions (structure with mass M_s + M_a);
//  * the drum film of TestScenes.hpp as a StructureParticipant under such a fluid, and its monolithic film
//    (density (1 + mu) rho).
// Derivations: docs/COUPLING.md.
#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "TestScenes.hpp"
#include "coupling/StructureParticipant.hpp"
#include "coupling/scheme/Acceleration.hpp"
#include "coupling/scheme/CouplingScheme.hpp"
#include "coupling/scheme/TimeInterpolation.hpp"
#include "coupling/scheme/acceleration/Aitken.hpp"
#include "coupling/scheme/acceleration/ConstantRelaxation.hpp"
#include "coupling/scheme/acceleration/IqnIls.hpp"
#include "structure/scene/Scene.hpp"

namespace fsi::test::reduced {

using namespace fsi::coupling;
using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kPi = 3.14159265358979323846;

using Forcing = std::function<VectorXd(double)>;

// How the fluid turns the interface displacements it is given into the interface acceleration its added
// mass reacts to. Newmark: the structure's own rule, so the converged implicit scheme IS the monolithic
// Newmark scheme. Bdf2: like an ALE solver's backward scheme (mesh velocity and flux acceleration by BDF2).
enum class Kinematics { Newmark, Bdf2 };

// Incompressible fluid reduced to its added mass: loads f = -M_a b + F(t).
class AddedMassFluid final : public FluidSolver {
 public:
  AddedMassFluid(MatrixXd ma, Forcing forcing, Kinematics kin, const VectorXd& x0, const VectorXd& v0,
                 const VectorXd& a0)
      : ma_(std::move(ma)), forcing_(std::move(forcing)), kin_(kin) {
    s_ = {x0, x0, v0, v0, a0, 0};
  }
  /// A diagonal added mass, given by its diagonal (for large interface meshes).
  AddedMassFluid(const VectorXd& maDiagonal, Forcing forcing, Kinematics kin, const VectorXd& x0,
                 const VectorXd& v0, const VectorXd& a0)
      : maDiagonal_(maDiagonal), forcing_(std::move(forcing)), kin_(kin) {
    s_ = {x0, x0, v0, v0, a0, 0};
  }
  VectorXd solve(double t, double dt, const VectorXd& d) override {
    ++solves;
    VectorXd b;
    if (kin_ == Kinematics::Newmark) {
      b = 4.0 / (dt * dt) * (d - s_.x - dt * s_.u) - s_.b;
      s_.u += 0.5 * dt * (s_.b + b);
    } else if (s_.steps == 0) {  // BDF1 start: no history yet
      const VectorXd w = (d - s_.x) / dt;
      b = (w - s_.u) / dt;
      s_.um1 = s_.u;
      s_.u = w;
    } else {
      const VectorXd w = (3.0 * d - 4.0 * s_.x + s_.xm1) / (2.0 * dt);
      b = (3.0 * w - 4.0 * s_.u + s_.um1) / (2.0 * dt);
      s_.um1 = s_.u;
      s_.u = w;
    }
    s_.xm1 = s_.x;
    s_.x = d;
    s_.b = b;
    ++s_.steps;
    if (maDiagonal_.size() > 0) return -maDiagonal_.cwiseProduct(b) + forcing_(t + dt);
    return -ma_ * b + forcing_(t + dt);
  }
  void saveCheckpoint() override {
    saved_ = s_;
    ++saves;
  }
  void restoreCheckpoint() override {
    s_ = saved_;
    ++restores;
  }
  int solves = 0, saves = 0, restores = 0;

 private:
  struct State {
    VectorXd x, xm1, u, um1, b;
    int steps;
  };
  MatrixXd ma_;
  VectorXd maDiagonal_;  // instead of ma_ when not empty
  Forcing forcing_;
  Kinematics kin_;
  State s_, saved_;
};

// Newmark average acceleration (beta 1/4, gamma 1/2): unconditionally stable, so any instability seen
// with it comes from the coupling. Equilibrium at t+dt uses the window's end loads; the start loads are
// already in the stored acceleration.
class NewmarkStructure final : public StructureSolver {
 public:
  NewmarkStructure(MatrixXd m, MatrixXd c, MatrixXd k, const VectorXd& x0, const VectorXd& v0,
                   const VectorXd& f0)
      : m_(std::move(m)), c_(std::move(c)), k_(std::move(k)) {
    s_ = {x0, v0, m_.ldlt().solve(f0 - c_ * v0 - k_ * x0)};
  }
  VectorXd solve(double, double dt, const VectorXd&, const VectorXd& fEnd) override {
    if (dt != dt_) {
      dt_ = dt;
      lhs_.compute(m_ + 0.5 * dt * c_ + 0.25 * dt * dt * k_);
    }
    const VectorXd xp = s_.x + dt * s_.v + 0.25 * dt * dt * s_.a;
    const VectorXd vp = s_.v + 0.5 * dt * s_.a;
    s_.a = lhs_.solve(fEnd - c_ * vp - k_ * xp);
    s_.x = xp + 0.25 * dt * dt * s_.a;
    s_.v = vp + 0.5 * dt * s_.a;
    return s_.x;
  }
  void saveCheckpoint() override { saved_ = s_; }
  void restoreCheckpoint() override { s_ = saved_; }
  const VectorXd& velocity() const { return s_.v; }

 private:
  struct State {
    VectorXd x, v, a;
  };
  MatrixXd m_, c_, k_;
  double dt_ = -1.0;
  Eigen::LDLT<MatrixXd> lhs_;
  State s_, saved_;
};

struct Problem {
  MatrixXd ms, c, k, ma;
  Forcing forcing;
  VectorXd x0, v0;
  std::function<VectorXd(double)> exact;  // monolithic solution, continuous in time
  double mu = 0.0;                        // added-mass ratio (largest eigenvalue of M_s^-1 M_a)

  VectorXd a0() const { return (ms + ma).ldlt().solve(forcing(0.0) - c * v0 - k * x0); }
  VectorXd f0() const { return -ma * a0() + forcing(0.0); }
  // Eigenvalues of (M_s + c dt/2 + K dt^2/4)^-1 M_a: minus the Jacobian of the Newmark fixed-point map.
  VectorXd iterationSpectrum(double dt) const {
    const MatrixXd a = ms + 0.5 * dt * c + 0.25 * dt * dt * k;
    return Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd>(ma, a, Eigen::EigenvaluesOnly).eigenvalues();
  }
};

inline MatrixXd scalar(double v) {
  return MatrixXd::Constant(1, 1, v);
}

// Piston: m_s = 1, m_a = mu, omega = sqrt(k / (1 + mu)) set by omegaDt at dt = 1; x(0) = 1, v(0) = 0;
// F(t) = forcing k sin(ratio omega t).
inline Problem piston(double mu, double omegaDt, double forcing = 0.0, double ratio = 0.5,
                      double damping = 0.0) {
  Problem p;
  const double mTot = 1.0 + mu, k = omegaDt * omegaDt * mTot, w = omegaDt, wf = ratio * w, f0 = forcing * k;
  p.ms = scalar(1.0);
  p.ma = scalar(mu);
  p.k = scalar(k);
  p.c = scalar(damping);
  p.forcing = [=](double t) { return VectorXd::Constant(1, f0 * std::sin(wf * t)); };
  p.x0 = VectorXd::Constant(1, 1.0);
  p.v0 = VectorXd::Zero(1);
  p.mu = mu;
  p.exact = [=](double t) {  // undamped only
    return VectorXd::Constant(
        1, std::cos(w * t) + f0 / (k - mTot * wf * wf) * (std::sin(wf * t) - wf / w * std::sin(w * t)));
  };
  return p;
}

// String of length 1 with n free nodes, node mass h, tension set by omega1Dt (fundamental with added mass,
// at dt = 1). Added mass of sine mode j: mu m / j (a potential flow pushes more fluid for long waves), so
// M_a = Phi diag(mu m / j) Phi^T is full. Uniform pressure p0 sin(ratio omega_1 t) with p0 = 8 T forcing
// (forcing = static mid-span deflection); starts at rest.
inline Problem stringModel(int n, double mu, double omega1Dt, double forcing = 0.01, double ratio = 0.5) {
  Problem p;
  const double h = 1.0 / (n + 1), m = h;
  MatrixXd phi(n, n);
  VectorXd kj(n), maj(n);
  for (int j = 1; j <= n; ++j) {
    for (int i = 1; i <= n; ++i)
      phi(i - 1, j - 1) = std::sqrt(2.0 / (n + 1)) * std::sin(kPi * i * j / (n + 1));
    const double s = std::sin(kPi * j / (2.0 * (n + 1)));
    kj(j - 1) = 4.0 * s * s / h;  // per unit tension
    maj(j - 1) = mu * m / j;
  }
  const double tension = omega1Dt * omega1Dt * (m + maj(0)) / kj(0);
  kj *= tension;
  p.k = MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    p.k(i, i) = 2.0 * tension / h;
    if (i + 1 < n) p.k(i, i + 1) = p.k(i + 1, i) = -tension / h;
  }
  p.ms = m * MatrixXd::Identity(n, n);
  p.c = MatrixXd::Zero(n, n);
  p.ma = phi * maj.asDiagonal() * phi.transpose();
  const double p0 = 8.0 * tension * forcing, wf = ratio * omega1Dt;
  const VectorXd shape = VectorXd::Constant(n, p0 * h);
  p.forcing = [=](double t) -> VectorXd { return shape * std::sin(wf * t); };
  p.x0 = VectorXd::Zero(n);
  p.v0 = VectorXd::Zero(n);
  p.mu = mu;
  const VectorXd fj = phi.transpose() * shape;
  p.exact = [=](double t) -> VectorXd {
    VectorXd q(n);
    for (int j = 0; j < n; ++j) {
      const double mj = m + maj(j), wj = std::sqrt(kj(j) / mj);
      q(j) = fj(j) / (kj(j) - mj * wf * wf) * (std::sin(wf * t) - wf / wj * std::sin(wj * t));
    }
    return phi * q;
  };
  return p;
}

// Makes a fresh acceleration for one run.
using AccelerationFactory = std::function<std::unique_ptr<Acceleration>()>;

struct RunSetup {
  SchemeKind scheme = SchemeKind::Implicit;
  double dt = 1.0;
  int windows = 100;
  int extrapolationOrder = 1;
  AccelerationFactory acceleration;
  double relTol = 1e-8;
  int maxIterations = 500;
  Kinematics kinematics = Kinematics::Newmark;
  double blowUp = 1e6;  // stop once |d| exceeds this many times the largest monolithic |d|
};

struct Trace {
  std::vector<VectorXd> d;  // accepted end-of-window displacements, d[0] = x0
  CouplingStatistics stats;
  bool blewUp = false;
};

inline std::vector<VectorXd> monolithic(const Problem& p, double dt, int windows) {
  NewmarkStructure s(p.ms + p.ma, p.c, p.k, p.x0, p.v0, p.forcing(0.0));
  std::vector<VectorXd> d{p.x0};
  for (int w = 0; w < windows; ++w) d.push_back(s.solve(w * dt, dt, VectorXd(), p.forcing((w + 1) * dt)));
  return d;
}

inline double maxNorm(const std::vector<VectorXd>& d) {
  double m = 0.0;
  for (const VectorXd& v : d) m = std::max(m, v.norm());
  return m;
}

// max_t |a(t) - b(t)| / max_t |b(t)|
inline double relativeDifference(const std::vector<VectorXd>& a, const std::vector<VectorXd>& b) {
  double e = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) e = std::max(e, (a[i] - b[i]).norm());
  return e / maxNorm(b);
}

inline std::vector<VectorXd> sampleExact(const Problem& p, double dt, int windows) {
  std::vector<VectorXd> d;
  for (int w = 0; w <= windows; ++w) d.push_back(p.exact(w * dt));
  return d;
}

inline Trace simulate(const Problem& p, const RunSetup& s) {
  AddedMassFluid fluid(p.ma, p.forcing, s.kinematics, p.x0, p.v0, p.a0());
  NewmarkStructure newmark(p.ms, p.c, p.k, p.x0, p.v0, p.f0());
  StructureSolver& structure = newmark;

  CouplingConfig cfg;
  cfg.kind = s.scheme;
  cfg.timeWindowSize = s.dt;
  cfg.endTime = s.windows * s.dt;
  cfg.extrapolationOrder = s.extrapolationOrder;
  cfg.relativeTolerance = s.relTol;
  cfg.absoluteTolerance = 1e-14;
  cfg.maxIterations = s.maxIterations;
  CouplingScheme scheme(cfg, structure, s.scheme == SchemeKind::Implicit ? s.acceleration() : nullptr);

  const double limit = s.blowUp * std::max(maxNorm(monolithic(p, s.dt, s.windows)), 1e-300);
  Trace tr;
  scheme.initialize(0.0, p.x0, p.f0());
  tr.d.push_back(p.x0);
  while (scheme.isCouplingOngoing()) {
    runTimeWindow(scheme, fluid);
    tr.d.push_back(scheme.acceptedDisplacement());
    if (tr.d.back().norm() > limit) {
      tr.blewUp = true;
      break;
    }
  }
  tr.stats = scheme.statistics();
  return tr;
}

inline AccelerationFactory constant(double omega) {
  return [omega] { return std::make_unique<ConstantRelaxation>(omega); };
}
inline AccelerationFactory aitken() {
  return [] { return std::make_unique<Aitken>(); };
}
inline AccelerationFactory iqn(int reuse = 0) {
  return [reuse] {
    IqnIlsOptions o;
    o.reuseSteps = reuse;
    return std::make_unique<IqnIls>(o);
  };
}
// Seeded, so the result does not depend on which other tests ran before (Eigen's Random uses rand()).
inline MatrixXd randomOrthogonal(int n) {
  std::mt19937 gen(12345);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  MatrixXd a(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) a(i, j) = u(gen);
  return Eigen::HouseholderQR<MatrixXd>(a).householderQ();
}
// The best constant factor for a known spectrum [lmin, lmax] of -J: 2 / (2 + lmin + lmax).
inline double optimalOmega(const VectorXd& spectrum) {
  // Plain min/max: GCC 12 with -march=native warns falsely inside Eigen's vectorised minCoeff.
  const double* b = spectrum.data();
  const double* e = b + spectrum.size();
  return 2.0 / (2.0 + *std::min_element(b, e) + *std::max_element(b, e));
}

// The structure of these tests is the product's: the drum film of TestScenes.hpp as a StructureParticipant
// (its CentralDifference through SubcycledStructure, the path of a coupled run). The fluid stays reduced: an
// added mass mu M_s on the film's nodes (M_s its lumped mass) with the BDF2 kinematics of an ALE solver, plus
// a known load F(t) = F_p sin(omega t) (F_p: the nodal forces of 200 Pa on the flat film). The monolithic
// answer is the same film with density (1 + mu) rho under F(t) alone (a membrane's lumped mass is
// proportional to its density), integrated with windows ten times shorter.

inline const std::string kFilm = fsi::test::drumScene(R"(coupling: {interface: sheet}
time: {end: 1.0}
)");

inline const char* sceneName(LoadInterpolation interp) {
  return interp == LoadInterpolation::ConstantMean  ? "mean"
         : interp == LoadInterpolation::ConstantEnd ? "end"
                                                    : "linear";
}

inline std::unique_ptr<StructureParticipant> film(double densityFactor, LoadInterpolation interp,
                                                  int minSubcycles = 1) {
  ParticipantOptions options;
  options.loadKind = fsi::structure::InterfaceLoadKind::NodalForces;
  options.minSubcycles = minSubcycles;
  return std::make_unique<StructureParticipant>(
      fsi::structure::loadSceneFromString(kFilm, "film.yaml",
                                          {"materials.film.density=" + std::to_string(1000.0 * densityFactor),
                                           std::string("coupling.load_in_window=") + sceneName(interp)}),
      options);
}

constexpr double kFilmWindow = 1e-3;
constexpr int kFilmWindows = 100;

// F(t): 200 Pa on the flat film, lumped (A/3 per triangle node), along z, times sin(omega t) with a period
// of 40 windows.
inline Forcing filmForcing(const StructureParticipant& s, double window = kFilmWindow) {
  const InterfaceMesh& m = s.interfaceMesh();
  VectorXd fp = VectorXd::Zero(3 * Eigen::Index(m.points.size()));
  const std::vector<int>& tris = m.faceNodes;  // the structure's faces are its triangles
  for (std::size_t e = 0; e + 2 < tris.size(); e += 3) {
    const auto& a = m.points[std::size_t(tris[e])];
    const auto& b = m.points[std::size_t(tris[e + 1])];
    const auto& c = m.points[std::size_t(tris[e + 2])];
    const double area = 0.5 * std::abs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    for (int k = 0; k < 3; ++k) fp(3 * Eigen::Index(tris[e + std::size_t(k)]) + 2) += 200.0 * area / 3.0;
  }
  const double omega = 2.0 * kPi / (40 * window);
  return [fp, omega](double t) -> VectorXd { return fp * std::sin(omega * t); };
}

// The monolithic film: density (1 + mu) rho, F(t) as nodal forces, `fine` steps per coupling window
// (`window`, `windows` of them).
inline std::vector<VectorXd> monolithicFilm(double mu, double window = kFilmWindow,
                                            int windows = kFilmWindows, int fine = 10) {
  auto s = film(1.0 + mu, LoadInterpolation::Linear);
  const Forcing f = filmForcing(*s, window);
  const double h = window / fine;
  std::vector<VectorXd> d{VectorXd::Zero(3 * s->numInterfaceNodes())};
  for (int w = 0; w < windows * fine; ++w) {
    const VectorXd u = s->solve(w * h, h, f(w * h), f((w + 1) * h));
    if ((w + 1) % fine == 0) d.push_back(u);
  }
  return d;
}

struct FilmRun {
  std::vector<VectorXd> d;  // accepted end-of-window interface displacements, d[0] = 0
  int substeps = 0;         // structural steps per window (the last window's)
  bool blewUp = false;
  CouplingStatistics stats;
  long structuralSteps = 0;             // every pass of every window, repeated ones included
  fsi::structure::EnergyLedger energy;  // the structure's bookkeeping at the end
};

// How the film is coupled to its reduced fluid. The subcycling tests use the defaults (implicit, IQN-ILS
// reusing 4 windows); the scheme tests vary the scheme and the acceleration.
struct FilmCoupling {
  LoadInterpolation interp = LoadInterpolation::ConstantMean;
  int minSubcycles = 1;
  SchemeKind scheme = SchemeKind::Implicit;
  AccelerationFactory acceleration = iqn(4);
  int maxIterations = 200;
  double window = kFilmWindow;  // the fluid's step; F(t) has a period of 40 of them
  int windows = kFilmWindows;
  double relativeTolerance = 1e-8;
};

inline FilmCoupling subcycled(LoadInterpolation interp, int minSubcycles) {
  FilmCoupling c;
  c.interp = interp;
  c.minSubcycles = minSubcycles;
  return c;
}

// The reduced fluid of coupledFilm on another interface mesh (test_hard_coupling.cpp): made for the
// participant `s`, the added-mass ratio `mu` and the window's forcing period.
using FilmFluidFactory =
    std::function<std::unique_ptr<FluidSolver>(const StructureParticipant& s, double mu)>;

inline FilmRun coupledFilm(double mu, const FilmCoupling& c, const FilmFluidFactory& makeFluid = {}) {
  auto s = film(1.0, c.interp, c.minSubcycles);
  const fsi::structure::Nodes& N = s->scene().model->nodes;
  const std::vector<int>& nodes = s->scene().couplingInterface->nodes;
  const Eigen::Index n = 3 * Eigen::Index(nodes.size());
  VectorXd ma(n);  // M_a = mu M_s on every dof
  for (std::size_t i = 0; i < nodes.size(); ++i)
    for (int k = 0; k < 3; ++k) ma(Eigen::Index(3 * i) + k) = mu * N.mass[std::size_t(nodes[i])];
  const VectorXd zero = VectorXd::Zero(n);
  // F(0) = 0 and the film starts at rest: a(0) = 0.
  AddedMassFluid ownFluid(MatrixXd(ma.asDiagonal()), filmForcing(*s, c.window), Kinematics::Bdf2, zero, zero,
                          zero);
  const std::unique_ptr<FluidSolver> otherFluid = makeFluid ? makeFluid(*s, mu) : nullptr;
  FluidSolver& fluid = otherFluid ? *otherFluid : ownFluid;
  CouplingConfig cfg;
  cfg.kind = c.scheme;
  cfg.timeWindowSize = c.window;
  cfg.endTime = c.windows * c.window;
  cfg.relativeTolerance = c.relativeTolerance;
  cfg.absoluteTolerance = 1e-14;
  cfg.maxIterations = c.maxIterations;
  CouplingScheme scheme(cfg, *s, c.scheme == SchemeKind::Implicit ? c.acceleration() : nullptr);
  scheme.initialize(0.0, zero, zero);
  FilmRun r;
  r.d.push_back(zero);
  while (scheme.isCouplingOngoing()) {
    try {
      runTimeWindow(scheme, fluid);
    } catch (const StructureUnstable&) {
      r.blewUp = true;
      break;
    }
    r.d.push_back(scheme.acceptedDisplacement());
    if (!r.d.back().allFinite() || r.d.back().norm() > 1e3) {
      r.blewUp = true;
      break;
    }
  }
  if (!r.blewUp) r.substeps = s->subcyclesFor(c.window);
  r.stats = scheme.statistics();
  r.structuralSteps = s->structuralSteps();
  r.energy = s->integrator().energy();
  return r;
}

}  // namespace fsi::test::reduced
