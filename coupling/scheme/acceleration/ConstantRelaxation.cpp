#include "coupling/scheme/acceleration/ConstantRelaxation.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace fsi::coupling {

// Relaxation factors are limited to (0, 1]: on an added-mass problem the iteration Jacobian has eigenvalues
// -lambda <= 0, and a factor above 1 contracts no mode better than 1 does (docs/COUPLING.md). The adapter's
// option table (CouplingOptions) has the same ranges.
ConstantRelaxation::ConstantRelaxation(double omega) : omega_(omega) {
  if (!(omega > 0.0 && omega <= 1.0))
    throw std::invalid_argument(
        fmt::format("ConstantRelaxation: omega = {:g}, valid: 0 < omega <= 1", omega));
}

Eigen::VectorXd ConstantRelaxation::compute(const Eigen::VectorXd& d, const Eigen::VectorXd& dTilde) {
  return d + omega_ * (dTilde - d);
}

AccelerationEntry constantRelaxationEntry() {
  return {"constant",
          "fixed relaxation d + omega r",
          {omegaOption("0.5", "the relaxation factor")},
          [](const OptionValues& v) -> std::unique_ptr<Acceleration> {
            return std::make_unique<ConstantRelaxation>(v.real("omega"));
          }};
}

}  // namespace fsi::coupling
