#include "coupling/scheme/acceleration/Aitken.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fsi::coupling {

Aitken::Aitken(AitkenOptions options) : opt_(options), omega_(options.initialOmega) {
  if (!(opt_.minOmega > 0.0 && opt_.minOmega <= opt_.maxOmega))
    throw std::invalid_argument("Aitken: need 0 < minOmega <= maxOmega");
  // The first factor is clamped to [minOmega, maxOmega] like every other one.
  if (!(opt_.initialOmega > 0.0 && opt_.initialOmega <= 1.0))
    throw std::invalid_argument(
        fmt::format("Aitken: initialOmega = {:g}, valid: 0 < initialOmega <= 1", opt_.initialOmega));
}

double Aitken::clampOmega(double w) const {
  const double s = w < 0.0 ? -1.0 : 1.0;
  return s * std::clamp(std::abs(w), opt_.minOmega, opt_.maxOmega);
}

Eigen::VectorXd Aitken::compute(const Eigen::VectorXd& d, const Eigen::VectorXd& dTilde) {
  Eigen::VectorXd r = dTilde - d;
  if (iteration_ == 0) {
    const double previous = omega_;
    omega_ = firstWindow_ ? opt_.initialOmega
                          : std::copysign(std::min(opt_.initialOmega, std::abs(previous)), previous);
  } else {
    const Eigen::VectorXd dr = r - previousResidual_;
    const double den = dr.squaredNorm();
    // A zero difference carries no curvature information: keep the last factor.
    if (den > 0.0) omega_ = -omega_ * previousResidual_.dot(dr) / den;
  }
  omega_ = clampOmega(omega_);
  previousResidual_ = r;
  ++iteration_;
  return d + omega_ * r;
}

void Aitken::onTimeWindowComplete(bool /*converged*/) {
  firstWindow_ = false;
  iteration_ = 0;
}

AccelerationEntry aitkenEntry() {
  return {"aitken",
          "Aitken's dynamic relaxation",
          {omegaOption("0.5", "relaxation factor of the first iteration; later ones are Aitken's")},
          [](const OptionValues& v) -> std::unique_ptr<Acceleration> {
            AitkenOptions o;
            o.initialOmega = v.real("omega");
            return std::make_unique<Aitken>(o);
          }};
}

}  // namespace fsi::coupling
