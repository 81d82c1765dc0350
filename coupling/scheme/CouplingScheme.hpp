#pragma once
// CouplingScheme: serial staggered (explicit) or iterated (implicit) coupling of a fluid that drives the
// time loop with an in-process structure. The fluid side talks to it like a preCICE participant, so an
// OpenFOAM function object can call it from execute():
//
//   double dt = scheme.initialize(t0, d0, loads0);
//   while (scheme.isCouplingOngoing()) {
//     if (scheme.requiresWritingCheckpoint()) fluid.saveCheckpoint();
//     moveMesh(scheme.displacement());                 // interface position at t + dt
//     Eigen::VectorXd loads = fluid.solve(scheme.time(), dt, ...);
//     dt = scheme.advance(loads);                      // structure solve, convergence test, acceleration
//     if (scheme.requiresReadingCheckpoint()) fluid.restoreCheckpoint();  // repeat the same window
//   }
//
// runTimeWindow() is that loop body for a FluidSolver. The structure is checkpointed by the scheme itself.
// Windows have a constant size; data are the interface displacement (structure -> fluid) and the interface
// loads (fluid -> structure). See docs/COUPLING.md.

#include <Eigen/Dense>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "coupling/scheme/Acceleration.hpp"
#include "coupling/scheme/Solvers.hpp"

namespace fsi::coupling {

enum class SchemeKind { Staggered, Implicit };

/// What to change after the structure became unstable inside a coupled window (the adapter's stop message
/// ends with it). A light structure in a dense fluid (the fluid's added mass above the structure's own) makes
/// every staggered exchange unstable whatever the step (docs/COUPLING.md, "Added mass"; the HardCoupling
/// tests): for the staggered scheme the implicit one is the cure, and a smaller step only for a heavy
/// structure.
std::string unstableStructureAdvice(SchemeKind kind);

struct CouplingConfig {
  SchemeKind kind = SchemeKind::Implicit;
  double timeWindowSize = 0.0;  ///< the fluid's step
  double endTime = std::numeric_limits<double>::infinity();
  /// First input of a window: polynomial extrapolation of the accepted end-of-window displacements of
  /// order 0 (d_n), 1 (2 d_n - d_{n-1}) or 2 (3 d_n - 3 d_{n-1} + d_{n-2}); lower while history is short.
  /// For the staggered scheme this predictor sets the added-mass stability limit (docs/COUPLING.md).
  int extrapolationOrder = 1;
  // Implicit only: converged when |d~ - d| <= relativeTolerance |d~| or |d~ - d| <= absoluteTolerance.
  double relativeTolerance = 1e-6;
  double absoluteTolerance = 1e-12;
  int maxIterations = 50;
  bool throwOnNonConvergence = false;  ///< else the window is accepted and reported as not converged
  /// Under-relaxed load transfer, 0 < ω <= 1 (1: off): the structure gets ω f + (1 − ω) f_prev as the
  /// window's end load, f the fluid's load and f_prev the load it got at the end of the previous window (the
  /// fluid's load at t0 for the first). Damps an oscillating load–shape feedback on the way to a steady state
  /// (docs/COUPLING.md "Coupling to equilibrium"); the converged steady state is the same, the path in time
  /// is not (a lag of about (1 − ω) / ω windows).
  double loadRelaxation = 1.0;
};

struct WindowReport {
  int window = -1;              ///< 0-based index
  double time = 0.0, dt = 0.0;  ///< the window is [time, time + dt]
  int iterations = 0;
  bool converged = false;
  double residualNorm = 0.0;      ///< |d~ - d| of the accepted iteration (0 for the staggered scheme)
  double relativeResidual = 0.0;  ///< |d~ - d| / |d~|
};

struct CouplingStatistics {
  int windows = 0, iterations = 0, maxIterations = 0, notConverged = 0;
  double meanIterations() const { return windows > 0 ? double(iterations) / windows : 0.0; }
};

class CouplingError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class CouplingScheme {
 public:
  /// `acceleration` is required for the implicit scheme and ignored by the staggered one.
  CouplingScheme(const CouplingConfig& config, StructureSolver& structure,
                 std::unique_ptr<Acceleration> acceleration = nullptr);

  /// Start at t0 with the interface displacement and the fluid's loads at t0; returns the window size.
  double initialize(double t0, const Eigen::VectorXd& displacement0, const Eigen::VectorXd& loads0);

  /// After initialize(): continue a run whose accepted end displacements were `newestFirst` (the first is
  /// the current displacement; at most 3 are used), so a restart predicts like the uninterrupted run.
  void restoreHistory(const std::vector<Eigen::VectorXd>& newestFirst);
  /// After initialize(): continue a run whose structure got `loads` at the end of its last accepted window
  /// (loadsAtWindowStart() of that run), so that a restarted run relaxes its loads (loadRelaxation < 1) like
  /// the uninterrupted one.
  void restoreLoadsAtWindowStart(const Eigen::VectorXd& loads);
  /// What the implicit scheme's acceleration carries between windows (empty for the staggered scheme, or
  /// an acceleration that carries nothing), and its restore after initialize(): a restarted run iterates
  /// like the uninterrupted one (IQN-ILS' reused columns, Aitken's last factor).
  Acceleration::State accelerationState() const {
    return acceleration_ && config_.kind == SchemeKind::Implicit ? acceleration_->state()
                                                                 : Acceleration::State{};
  }
  void restoreAccelerationState(const Acceleration::State& state) {
    if (acceleration_ && config_.kind == SchemeKind::Implicit) acceleration_->restore(state);
  }
  /// Accepted end displacements, newest first (what restoreHistory() takes).
  const std::vector<Eigen::VectorXd>& history() const { return history_; }

  /// Hand over the fluid's loads at the end of the current window (for the current displacement()); runs
  /// the structure and decides whether the window is complete. Returns the size of the next solve.
  double advance(const Eigen::VectorXd& loads);

  bool isCouplingOngoing() const;
  /// The next fluid solve starts a window (implicit only): save the fluid state now.
  bool requiresWritingCheckpoint() const;
  /// The last advance() rejected the iterate: restore the fluid to the start of the window and solve again.
  /// Stays true until the next advance(); restoring twice is harmless.
  bool requiresReadingCheckpoint() const;
  /// The last advance() accepted a window (false after initialize()).
  bool isTimeWindowComplete() const { return windowComplete_; }

  /// Interface displacement the fluid imposes at time() + timeWindowSize() in its next solve.
  const Eigen::VectorXd& displacement() const { return input_; }
  /// The structure's displacement at the end of the last accepted window (d0 after initialize()).
  const Eigen::VectorXd& acceptedDisplacement() const { return history_.front(); }
  /// Loads at the start of the current window (the accepted end loads of the previous one, as the structure
  /// got them: relaxed when CouplingConfig::loadRelaxation < 1).
  const Eigen::VectorXd& loadsAtWindowStart() const { return loadsStart_; }
  double time() const { return t_; }  ///< start of the current window
  double timeWindowSize() const { return config_.timeWindowSize; }
  int iteration() const { return iteration_; }  ///< 0-based iteration within the current window
  int window() const { return window_; }        ///< 0-based index of the current window

  const WindowReport& lastWindow() const { return last_; }
  const CouplingStatistics& statistics() const { return stats_; }
  const CouplingConfig& config() const { return config_; }

 private:
  void requireInitialized(const char* what) const;
  void completeWindow(const Eigen::VectorXd& loads, const Eigen::VectorXd& dEnd, int iterations,
                      bool converged, double res, double rel);
  Eigen::VectorXd predictor() const;

  CouplingConfig config_;
  StructureSolver& structure_;
  std::unique_ptr<Acceleration> acceleration_;
  bool initialized_ = false, windowComplete_ = false;
  int window_ = 0, iteration_ = 0;
  double t0_ = 0.0, t_ = 0.0;
  Eigen::VectorXd input_, loadsStart_;
  std::vector<Eigen::VectorXd> history_;  // accepted end displacements, newest first, at most 3
  WindowReport last_;
  CouplingStatistics stats_;
};

/// One fluid time window through the participant API: checkpoint, solve, advance, restore, until the
/// scheme accepts the window. Returns that window's report.
WindowReport runTimeWindow(CouplingScheme& scheme, FluidSolver& fluid);

}  // namespace fsi::coupling
