#pragma once
// TimeFunction: a scalar multiplier f(t) for loads and prescribed motions.

#include <string>
#include <utility>
#include <vector>

namespace fsi::structure {

class TimeFunction {
 public:
  enum class Kind { Constant, Ramp, SmoothStep, Table, Sine };
  static TimeFunction constant(double value = 1.0);
  /// Linear rise from 0 at t=start to 1 at t=start+duration, then 1.
  static TimeFunction ramp(double duration, double start = 0.0);
  /// C1 rise 3s²−2s³ over the duration: no velocity kick at either end.
  static TimeFunction smoothStep(double duration, double start = 0.0);
  /// Piecewise linear through (t, value) points, constant outside; times strictly increasing.
  static TimeFunction table(std::vector<std::pair<double, double>> points);
  /// amplitude·sin(2π f t + phase) + offset
  static TimeFunction sine(double amplitude, double frequency, double phase = 0.0, double offset = 0.0);

  double operator()(double t) const;
  Kind kind() const { return kind_; }

 private:
  Kind kind_ = Kind::Constant;
  double a_ = 1, b_ = 0, c_ = 0, d_ = 0;
  std::vector<std::pair<double, double>> table_;
};

}  // namespace fsi::structure
