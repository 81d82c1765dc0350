#include "coupling/scheme/TimeInterpolation.hpp"

#include <stdexcept>

namespace fsi::coupling {

const char* toString(LoadInterpolation kind) {
  switch (kind) {
    case LoadInterpolation::ConstantMean:
      return "constant-mean";
    case LoadInterpolation::ConstantEnd:
      return "constant-end";
    case LoadInterpolation::Linear:
      return "linear";
  }
  return "?";
}

TimeInterpolation::TimeInterpolation(LoadInterpolation kind, const Eigen::VectorXd& start,
                                     const Eigen::VectorXd& end)
    : kind_(kind), start_(start), end_(end) {
  if (start.size() != end.size())
    throw std::invalid_argument("TimeInterpolation: start and end sizes differ");
}

void TimeInterpolation::at(double theta, Eigen::VectorXd& out) const {
  // start + s (end - start) for every rule (s = 1/2, 1 or theta): the form the structure's interface effect
  // always evaluated, so that moving the window rule here changed no coupled result by a single bit.
  const double s = kind_ == LoadInterpolation::ConstantMean  ? 0.5
                   : kind_ == LoadInterpolation::ConstantEnd ? 1.0
                                                             : theta;
  out = start_ + s * (end_ - start_);
}

}  // namespace fsi::coupling
