#include "flight/GlideSlope.hpp"

#include <algorithm>

namespace fsi::flight {

double GlideSlope::update(double dt, double requiredDeg, double flownDeg) {
  const double e = requiredDeg - flownDeg;
  const double de = first_ ? 0.0 : (e - lastError_) / dt;
  first_ = false;
  lastError_ = e;
  const double unclamped = p_.trim + p_.gains.kp * e + p_.gains.ki * integral_ + p_.gains.kd * de;
  // Anti-windup: integrate only while the output is not pushed further into its limit.
  if (!((unclamped >= p_.max && e > 0) || (unclamped <= p_.min && e < 0)))
    integral_ = std::clamp(integral_ + e * dt, -p_.gains.integralLimit, p_.gains.integralLimit);
  return std::clamp(p_.trim + p_.gains.kp * e + p_.gains.ki * integral_ + p_.gains.kd * de, p_.min, p_.max);
}

}  // namespace fsi::flight
