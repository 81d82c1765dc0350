#pragma once
// Interface loads inside one coupling window [t, t+dt], for a structure that takes several steps in it.
// The fluid only delivers the loads at the two ends of the window; these rules fill in between.
//
//   ConstantMean  (f_start + f_end) / 2 throughout: the window's trapezoidal impulse, the same as the
//                 fluid's own time integration gives. Stable with any added-mass ratio (docs/COUPLING.md).
//   ConstantEnd   f_end throughout: first order; slightly unstable with a heavy added mass.
//   Linear        f_start + theta (f_end - f_start): most accurate for loads that are not dominated by
//                 added mass, but its quadrature of the window differs from the fluid's, and with an
//                 added-mass ratio of order one or more the converged coupled scheme becomes unstable.

//
// The enum is the structure's (a scene's `coupling: {load_in_window: ...}` names it), so that the scene and
// the coupling share one definition; this is its only implementation.

#include <Eigen/Dense>

#include "structure/effects/InterfacePressure.hpp"

namespace fsi::coupling {

using structure::LoadInterpolation;

const char* toString(LoadInterpolation kind);

class TimeInterpolation {
 public:
  TimeInterpolation(LoadInterpolation kind, const Eigen::VectorXd& start, const Eigen::VectorXd& end);
  /// Loads at the fraction theta in [0, 1] of the window, written into `out` (resized if needed).
  void at(double theta, Eigen::VectorXd& out) const;
  Eigen::VectorXd at(double theta) const {
    Eigen::VectorXd out;
    at(theta, out);
    return out;
  }
  LoadInterpolation kind() const { return kind_; }

 private:
  LoadInterpolation kind_;
  Eigen::VectorXd start_, end_;  // copies: the caller's vectors may be temporaries
};

}  // namespace fsi::coupling
