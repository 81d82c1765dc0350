#pragma once
// Equilibrium: coupling to the structure's static equilibrium instead of its motion (structureMode
// equilibrium). Within every window the structure takes N damped pseudo-steps (equilibriumSteps, default
// 100, after Kalro & Tezduyar's 100 structural steps per fluid step for parachute inflation) under the
// window's end load held fixed, instead of integrating its physical motion over the fluid's Δt. Damping is
// kinetic (as the structure's dynamic relaxation, structure/integrate/DynamicRelaxation): the motion starts
// from rest in every window, and whenever the kinetic energy drops (a peak has passed) every velocity is set
// to zero. The pseudo-steps are the integrator's own stable steps, so N does not depend on Δt and the
// relaxation can neither be unstable nor lag behind a long window; the structure's clock is then set to the
// window's end. What the fluid sees is a sequence of quasi-static shapes: the interface velocity of the
// window is the displacement change over the window, (d_end - d_start) / Δt (the adapter's moving walls take
// exactly this from the mesh motion). For steady states only: the path in time is not physical
// (docs/COUPLING.md).
//
// The class drives any RelaxationStepper: StructureParticipant (the explicit membrane solver) in a coupled
// run, a reduced structure in the tests.

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "coupling/scheme/Solvers.hpp"

namespace fsi::coupling {

/// How the structure answers a window's load: its motion over Δt (time-accurate subcycling, Subcycling.hpp)
/// or the static equilibrium it relaxes towards (EquilibriumStructure).
enum class StructureMode { TimeAccurate, Equilibrium };
/// "timeAccurate", "equilibrium": the option's words, in the enum's order.
const std::vector<std::string>& structureModeNames();
std::string toString(StructureMode mode);

/// A structure that can be relaxed towards equilibrium one damped pseudo-step at a time.
class RelaxationStepper : public CheckpointedSolver {
 public:
  /// Holds `loads` (the solver's interface load kind) for the pseudo-steps that follow.
  virtual void freezeLoads(const Eigen::VectorXd& loads) = 0;
  /// One step of the structure's own stable size under the frozen loads; returns the kinetic energy after
  /// it. Throws (e.g. StructureUnstable) if the state becomes non-finite.
  virtual double relaxStep() = 0;
  /// Kinetic damping: every velocity to zero, the kinetic energy removed counted as dissipated.
  virtual void stopMotion() = 0;
  /// Sets the structure's clock to `t` without moving it (the pseudo-steps are not physical time); `velocity`
  /// (3 per interface node) is the interface velocity to report for the window just relaxed.
  virtual void endWindow(double t, const Eigen::VectorXd& velocity) = 0;
  virtual Eigen::VectorXd interfaceDisplacement() const = 0;
};

/// How a window's pseudo-motion starts: from rest (every window a fresh kinetic relaxation) or with the
/// pseudo-velocities the previous window ended with. Restarting from rest advances a slow mode (a canopy
/// swinging on its lines, period >> the N pseudo-steps) by only ~(N h)^2 a / 2 per window, however many
/// windows follow; carrying the motion lets it build up across windows, while the kinetic damping still
/// stops it at every kinetic-energy peak (docs/COUPLING.md, "Coupling to equilibrium").
enum class EquilibriumStart { Rest, Carry };
/// "rest", "carry": the option's words, in the enum's order.
const std::vector<std::string>& equilibriumStartNames();

struct EquilibriumOptions {
  int steps = 100;                                  ///< damped pseudo-steps per window (>= 1)
  EquilibriumStart start = EquilibriumStart::Rest;  ///< the window's pseudo-motion from rest or carried over
  /// Carry: the windows that start before this time still relax from rest. A start-up transient (an
  /// impulsive inflation) carried across windows builds up a motion the fluid mesh cannot follow; once it
  /// has died out, carrying converges the slow swing (docs/COUPLING.md, "Coupling to equilibrium").
  double carryFrom = 0.0;
};

/// What the last window's relaxation did (one row of coupling.csv in equilibrium mode).
struct EquilibriumReport {
  int steps = 0;           ///< pseudo-steps taken
  int resets = 0;          ///< kinetic-energy peaks at which the motion was stopped
  double lastKinetic = 0;  ///< kinetic energy after the last pseudo-step [J]
};

/// Makes a RelaxationStepper a StructureSolver for the coupling schemes: solve(t, dt, ., loadsEnd) relaxes
/// the structure under loadsEnd for options().steps pseudo-steps and returns the displacement it reached,
/// with the structure's clock at t + dt.
class EquilibriumStructure final : public StructureSolver {
 public:
  explicit EquilibriumStructure(RelaxationStepper& stepper, EquilibriumOptions options = {});
  Eigen::VectorXd solve(double t, double dt, const Eigen::VectorXd& loadsStart,
                        const Eigen::VectorXd& loadsEnd) override;
  void saveCheckpoint() override {
    stepper_.saveCheckpoint();
    savedKinetic_ = carriedKinetic_;
  }
  void restoreCheckpoint() override {
    stepper_.restoreCheckpoint();
    carriedKinetic_ = savedKinetic_;
  }
  const EquilibriumOptions& options() const { return opt_; }
  const EquilibriumReport& lastReport() const { return last_; }

 private:
  RelaxationStepper& stepper_;
  EquilibriumOptions opt_;
  EquilibriumReport last_;
  double carriedKinetic_ = 0;  ///< carry: the kinetic energy the peak test compares the next step with
  double savedKinetic_ = 0;    ///< carriedKinetic_ at the checkpoint (a repeated window starts from it)
};

}  // namespace fsi::coupling
