#pragma once
// The two participants as the coupling schemes see them: a black box that advances one time window from a
// saved state. Interface data are flat vectors in each solver's own interface numbering (the mapping
// between non-matching meshes happens outside, before and after these calls).

#include <Eigen/Dense>

namespace fsi::coupling {

/// A solver whose window can be repeated: the iterated scheme restores it to the start of the window
/// before every re-iteration, so each pass starts from exactly the same state.
class CheckpointedSolver {
 public:
  virtual ~CheckpointedSolver() = default;
  virtual void saveCheckpoint() = 0;
  virtual void restoreCheckpoint() = 0;
};

class FluidSolver : public CheckpointedSolver {
 public:
  /// Advance [t, t+dt] with the interface at `interfaceDisplacement` at t+dt; returns the interface loads
  /// at t+dt.
  virtual Eigen::VectorXd solve(double t, double dt, const Eigen::VectorXd& interfaceDisplacement) = 0;
};

class StructureSolver : public CheckpointedSolver {
 public:
  /// Advance [t, t+dt] under interface loads known at both ends of the window (how they vary in between is
  /// the solver's choice, see TimeInterpolation); returns the interface displacement at t+dt.
  virtual Eigen::VectorXd solve(double t, double dt, const Eigen::VectorXd& loadsStart,
                                const Eigen::VectorXd& loadsEnd) = 0;
};

}  // namespace fsi::coupling
