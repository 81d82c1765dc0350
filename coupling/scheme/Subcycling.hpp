#pragma once
// Subcycling: an explicit structure takes N = ceil(dt_window / dt_stable) equal steps per coupling window.
// The loads between the window's ends come from TimeInterpolation; the coupling only sees the displacement
// at the end of the window. N is recomputed per window (the stable step of a nonlinear membrane changes)
// but is fixed within one window, so every coupling iteration of that window repeats the same substeps.
// This is the path of the product: coupling/StructureParticipant is a StructureStepper over the structure's
// CentralDifference, made a StructureSolver by SubcycledStructure.

#include <Eigen/Dense>

#include "coupling/scheme/Solvers.hpp"
#include "coupling/scheme/TimeInterpolation.hpp"

namespace fsi::coupling {

/// Number of equal substeps of at most `stableStep` covering `windowSize`. A ratio that is an integer up
/// to round-off (3.0000000000004) gives that integer, not one more.
int subcycleCount(double windowSize, double stableStep);

/// A conditionally stable structural integrator seen one substep at a time.
class StructureStepper : public CheckpointedSolver {
 public:
  virtual double stableTimeStep() const = 0;
  /// Advance [t, t+h] with interface loads `loadsStart` at t and `loadsEnd` at t+h. The last substep of a
  /// window ends exactly on the window's end t_w + dt (h is the difference, not dt / N).
  virtual void step(double t, double h, const Eigen::VectorXd& loadsStart,
                    const Eigen::VectorXd& loadsEnd) = 0;
  virtual Eigen::VectorXd interfaceDisplacement() const = 0;
};

struct SubcyclingOptions {
  LoadInterpolation interpolation = LoadInterpolation::ConstantMean;
  double safety = 1.0;  ///< fraction of the stepper's stable step actually used
  int minSubsteps = 1;  ///< at least this many substeps per window (>= 1)
};

/// Makes a StructureStepper a StructureSolver for the coupling schemes.
class SubcycledStructure final : public StructureSolver {
 public:
  SubcycledStructure(StructureStepper& stepper, SubcyclingOptions options = {});
  Eigen::VectorXd solve(double t, double dt, const Eigen::VectorXd& loadsStart,
                        const Eigen::VectorXd& loadsEnd) override;
  void saveCheckpoint() override { stepper_.saveCheckpoint(); }
  void restoreCheckpoint() override { stepper_.restoreCheckpoint(); }
  /// Substeps a window of length dt takes from the stepper's current stable step.
  int substepsFor(double dt) const;
  const SubcyclingOptions& options() const { return opt_; }

 private:
  StructureStepper& stepper_;
  SubcyclingOptions opt_;
  Eigen::VectorXd f0_, f1_;
};

}  // namespace fsi::coupling
