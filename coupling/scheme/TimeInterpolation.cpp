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
  switch (kind_) {
    case LoadInterpolation::ConstantMean:
      out = 0.5 * (start_ + end_);
      return;
    case LoadInterpolation::ConstantEnd:
      out = end_;
      return;
    case LoadInterpolation::Linear:
      out = (1.0 - theta) * start_ + theta * end_;
      return;
  }
}

}  // namespace fsi::coupling
