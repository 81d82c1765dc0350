#pragma once
// GlideSlope: the autopilot's longitudinal loop. The glide path it holds runs from the system to the target
// over the waypoints still ahead: the required glide angle is atan(altitude / remaining distance over the
// ground). The error between that and the glide angle flown over the ground (atan(descent rate / ground
// speed): a head wind steepens it, and the loop sees that) drives a PID whose output, around a trim value and
// within [min, max], is one of the glide controls (flight/GlideControls: the rigging's incidence or the
// symmetric brake). Positive error: the system is above its path and must glide steeper.

#include <string>

#include "flight/PidGains.hpp"

namespace fsi::flight {

struct GlideSlopeParams {
  std::string control;                  ///< a glideControlKinds() name; empty: no glide-slope loop
  PidGains gains{1.0, 0.1, 0.0, 20.0};  ///< glide-angle error [deg] -> output (the kind's unit)
  double trim = 0, min = 0, max = 0;    ///< output at zero error and its limits (the kind's unit)
  bool enabled() const { return !control.empty(); }
};

class GlideSlope {
 public:
  explicit GlideSlope(GlideSlopeParams p) : p_(std::move(p)) {}
  /// The output for the glide angles [deg] required and flown, dt [s] after the last update.
  double update(double dt, double requiredDeg, double flownDeg);

 private:
  GlideSlopeParams p_;
  double integral_ = 0, lastError_ = 0;
  bool first_ = true;
};

}  // namespace fsi::flight
