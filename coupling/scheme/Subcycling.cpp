#include "coupling/scheme/Subcycling.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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
}

Eigen::VectorXd SubcycledStructure::solve(double t, double dt, const Eigen::VectorXd& loadsStart,
                                          const Eigen::VectorXd& loadsEnd) {
  const int n = subcycleCount(dt, opt_.safety * stepper_.stableTimeStep());
  const double h = dt / n;
  const TimeInterpolation loads(opt_.interpolation, loadsStart, loadsEnd);
  loads.at(0.0, f0_);
  for (int i = 0; i < n; ++i) {
    loads.at(double(i + 1) / n, f1_);
    stepper_.step(t + i * h, h, f0_, f1_);
    f0_.swap(f1_);
  }
  lastSubsteps_ = n;
  return stepper_.interfaceDisplacement();
}

}  // namespace fsi::coupling
