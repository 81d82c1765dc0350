#pragma once
// Guidance: the autopilot of the parafoil-payload system. Homing through waypoints with two PID loops, as the
// parafoil autopilots of the literature do: the course over the ground towards the current waypoint gives a
// yaw-rate command (outer loop, limited to max_yaw_rate), the yaw-rate error gives the differential brake
// (inner loop: a right turn pulls the right brake). A waypoint is passed within acceptance_radius; the last
// one is the target, which the system then keeps homing on (it circles it until it lands). The controller
// runs at a fixed rate and holds its output between updates (zero-order hold), like a flight computer. With
// `glide_slope` a second loop (flight/GlideSlope) holds the glide path to the target through the incidence or
// the symmetric brake.

#include <array>
#include <string>
#include <vector>

#include "flight/FlightSystem.hpp"
#include "flight/GlideSlope.hpp"
#include "flight/PidGains.hpp"

namespace fsi::flight {

struct GuidanceParams {
  std::vector<std::array<double, 2>> waypoints;  ///< north, east [m]; the last is the target
  double acceptanceRadius = 20;                  ///< [m]
  PidGains course{0.6, 0.0, 0.0};                ///< course error [rad] -> yaw-rate command [rad/s]
  double maxYawRate = 0.3;                       ///< [rad/s]
  PidGains yawRate{3.0, 0.5, 0.0, 0.5};          ///< yaw-rate error [rad/s] -> differential brake
  double maxBrake = 1.0;                         ///< largest brake on either side
  bool rightTurnPullsRight = true;               ///< false: the airframe turns away from the pulled brake
  double rate = 10;                              ///< controller updates per second [Hz]
  GlideSlopeParams glideSlope;                   ///< the longitudinal loop (off unless a control is named)
  bool enabled() const { return !waypoints.empty(); }
};

class Guidance {
 public:
  explicit Guidance(GuidanceParams params) : p_(std::move(params)), glide_(p_.glideSlope) {}
  /// The brakes for the next 1/rate seconds, from the state at time t.
  Controls update(double t, const FlightState& x);
  int waypoint() const { return current_; }  ///< index of the waypoint being homed on
  double nextUpdate() const { return next_; }
  const GuidanceParams& params() const { return p_; }
  /// The glide angle [deg] the glide-slope loop asked for at its last update (0 without that loop).
  double requiredGlideDeg() const { return requiredGlide_; }

 private:
  GuidanceParams p_;
  GlideSlope glide_;
  double requiredGlide_ = 0;
  int current_ = 0;
  double next_ = 0, last_ = -1;
  double courseIntegral_ = 0, rateIntegral_ = 0, lastCourseError_ = 0, lastRateError_ = 0;
  Controls held_;
};

/// Wraps an angle to (−π, π].
double wrapAngle(double a);

}  // namespace fsi::flight
