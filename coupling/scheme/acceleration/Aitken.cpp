#include "coupling/scheme/acceleration/Aitken.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "structure/model/Error.hpp"

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

Acceleration::State Aitken::state() const {
  return {{"omega", {omega_}}, {"first_window", {firstWindow_ ? 1.0 : 0.0}}};
}

void Aitken::restore(const State& state) {
  const auto omega = state.find("omega");
  const auto first = state.find("first_window");
  if (omega == state.end() || first == state.end())
    throw InputError("Aitken state: needs the arrays omega and first_window");
  if (omega->second.size() != 1 || !std::isfinite(omega->second[0]) || omega->second[0] == 0.0)
    throw InputError("Aitken state: omega must be one finite non-zero value");
  if (first->second.size() != 1 || (first->second[0] != 0.0 && first->second[0] != 1.0))
    throw InputError("Aitken state: first_window must be one value, 0 or 1");
  omega_ = clampOmega(omega->second[0]);
  firstWindow_ = first->second[0] != 0.0;
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
