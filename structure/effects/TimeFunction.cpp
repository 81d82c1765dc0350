#include "structure/effects/TimeFunction.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fsi::structure {

TimeFunction TimeFunction::constant(double value) {
  TimeFunction f;
  f.kind_ = Kind::Constant;
  f.a_ = value;
  return f;
}
TimeFunction TimeFunction::ramp(double duration, double start) {
  if (!(duration > 0)) throw std::invalid_argument("ramp duration must be > 0");
  TimeFunction f;
  f.kind_ = Kind::Ramp;
  f.a_ = duration;
  f.b_ = start;
  return f;
}
TimeFunction TimeFunction::smoothStep(double duration, double start) {
  TimeFunction f = ramp(duration, start);
  f.kind_ = Kind::SmoothStep;
  return f;
}
TimeFunction TimeFunction::table(std::vector<std::pair<double, double>> points) {
  if (points.empty()) throw std::invalid_argument("table needs at least one point");
  for (std::size_t i = 1; i < points.size(); ++i)
    if (!(points[i].first > points[i - 1].first)) throw std::invalid_argument("table times must increase");
  TimeFunction f;
  f.kind_ = Kind::Table;
  f.table_ = std::move(points);
  return f;
}
TimeFunction TimeFunction::sine(double amplitude, double frequency, double phase, double offset) {
  TimeFunction f;
  f.kind_ = Kind::Sine;
  f.a_ = amplitude;
  f.b_ = frequency;
  f.c_ = phase;
  f.d_ = offset;
  return f;
}

double TimeFunction::operator()(double t) const {
  switch (kind_) {
    case Kind::Constant:
      return a_;
    case Kind::Ramp:
      return std::clamp((t - b_) / a_, 0.0, 1.0);
    case Kind::SmoothStep: {
      const double s = std::clamp((t - b_) / a_, 0.0, 1.0);
      return s * s * (3.0 - 2.0 * s);
    }
    case Kind::Table: {
      if (t <= table_.front().first) return table_.front().second;
      if (t >= table_.back().first) return table_.back().second;
      const auto it = std::upper_bound(table_.begin(), table_.end(), t,
                                       [](double v, const auto& p) { return v < p.first; });
      const auto& p1 = *(it - 1);
      const auto& p2 = *it;
      return p1.second + (p2.second - p1.second) * (t - p1.first) / (p2.first - p1.first);
    }
    case Kind::Sine:
      return a_ * std::sin(2.0 * M_PI * b_ * t + c_) + d_;
  }
  return 0.0;
}

}  // namespace fsi::structure
