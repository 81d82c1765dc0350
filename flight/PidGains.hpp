#pragma once
// PidGains: the gains of one PID loop of the autopilot (flight/Guidance, flight/GlideSlope), from the flight
// file's `*_gains` keys.

namespace fsi::flight {

struct PidGains {
  double kp = 0, ki = 0, kd = 0;
  double integralLimit = 1e9;  ///< |∫e dt| is clamped here (anti-windup)
};

}  // namespace fsi::flight
