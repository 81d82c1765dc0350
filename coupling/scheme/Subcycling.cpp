#include "coupling/scheme/Subcycling.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace fsi::coupling {

int subcycleCount(double windowSize, double stableStep) {
  if (!(windowSize > 0.0) || !(stableStep > 0.0) || !std::isfinite(windowSize))
    throw std::invalid_argument("subcycleCount: window and stable step must be positive");
  if (!std::isfinite(stableStep)) return 1;  // unconditionally stable integrator
  const double ratio = windowSize / stableStep;
  if (ratio > 1e9) throw std::invalid_argument("subcycleCount: more than 1e9 substeps per window");
  return std::max(1, int(std::ceil(ratio * (1.0 - 1e-12))));
}

SubcycledStructure::SubcycledStructure(StructureStepper& stepper, SubcyclingOptions options)
    : stepper_(stepper), opt_(options) {
  if (!(opt_.safety > 0.0 && opt_.safety <= 1.0))
    throw std::invalid_argument("SubcycledStructure: safety must be in (0, 1]");
  if (opt_.minSubsteps < 1)
    throw std::invalid_argument("SubcycledStructure: minSubsteps = " + std::to_string(opt_.minSubsteps) +
                                ", valid: >= 1");
}

int SubcycledStructure::substepsFor(double dt) const {
  return std::max(opt_.minSubsteps, subcycleCount(dt, opt_.safety * stepper_.stableTimeStep()));
}

Eigen::VectorXd SubcycledStructure::solve(double t, double dt, const Eigen::VectorXd& loadsStart,
                                          const Eigen::VectorXd& loadsEnd) {
  const int n = substepsFor(dt);
  const double h = dt / n, tEnd = t + dt;
  const TimeInterpolation loads(opt_.interpolation, loadsStart, loadsEnd);
  loads.at(0.0, f0_);
  for (int i = 0; i < n; ++i) {
    loads.at(double(i + 1) / n, f1_);
    // The last substep ends on the window's end itself, so the structure's clock never drifts from the
    // scheme's by summing substeps.
    const double t0 = t + i * h, t1 = i + 1 == n ? tEnd : t + (i + 1) * h;
    stepper_.step(t0, t1 - t0, f0_, f1_);
    f0_.swap(f1_);
  }
  return stepper_.interfaceDisplacement();
}

}  // namespace fsi::coupling
