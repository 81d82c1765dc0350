#include "coupling/scheme/Equilibrium.hpp"

#include <stdexcept>
#include <string>

namespace fsi::coupling {

const std::vector<std::string>& structureModeNames() {
  static const std::vector<std::string> names{"timeAccurate", "equilibrium"};
  return names;
}

const std::vector<std::string>& equilibriumStartNames() {
  static const std::vector<std::string> names{"rest", "carry"};
  return names;
}

std::string toString(StructureMode mode) {
  return structureModeNames()[std::size_t(mode)];
}

EquilibriumStructure::EquilibriumStructure(RelaxationStepper& stepper, EquilibriumOptions options)
    : stepper_(stepper), opt_(options) {
  if (opt_.steps < 1)
    throw std::invalid_argument("EquilibriumStructure: equilibriumSteps = " + std::to_string(opt_.steps) +
                                ", valid: >= 1");
}

Eigen::VectorXd EquilibriumStructure::solve(double t, double dt, const Eigen::VectorXd& /*loadsStart*/,
                                            const Eigen::VectorXd& loadsEnd) {
  if (!(dt > 0.0)) throw std::invalid_argument("EquilibriumStructure: window size must be > 0");
  // The newest load only: the window's start load is what the previous window relaxed under already.
  const Eigen::VectorXd start = stepper_.interfaceDisplacement();
  stepper_.freezeLoads(loadsEnd);
  // Half a window's tolerance: the window that starts at carryFrom carries.
  const bool carry = opt_.start == EquilibriumStart::Carry && t + 0.5 * dt >= opt_.carryFrom;
  // From rest, every window is a fresh relaxation under the new load. Carried over, the pseudo-velocities
  // keep the direction the structure was relaxing in (the load changed by one fluid step only); a
  // kinetic-energy peak still stops them.
  if (!carry) stepper_.stopMotion();
  // Carried, the kinetic energy the last window ended with is the one to compare the first step with (a peak
  // may fall between two windows).
  double previous = carry ? carriedKinetic_ : 0.0;
  last_ = {};
  for (int i = 0; i < opt_.steps; ++i) {
    const double ke = stepper_.relaxStep();
    if (ke < previous) {
      // Past a peak of the kinetic energy: the structure is near the minimum of its potential along the path
      // it took; stop it there and let the forces start it again (kinetic damping).
      stepper_.stopMotion();
      ++last_.resets;
      previous = 0.0;
    } else {
      previous = ke;
    }
    last_.lastKinetic = ke;
  }
  last_.steps = opt_.steps;
  // A window from rest ends at rest: the first carried window's first step has nothing to compare with.
  carriedKinetic_ = carry ? previous : 0.0;
  // What is left of the pseudo-motion is not the structure's velocity: from rest, the window ends at rest;
  // carried, it is the next window's start.
  if (!carry) stepper_.stopMotion();
  const Eigen::VectorXd end = stepper_.interfaceDisplacement();
  stepper_.endWindow(t + dt, (end - start) / dt);
  return end;
}

}  // namespace fsi::coupling
