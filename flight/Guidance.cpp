#include "flight/Guidance.hpp"

#include <algorithm>
#include <cmath>

#include "flight/GlideControls.hpp"

namespace fsi::flight {

double wrapAngle(double a) {
  a = std::fmod(a + M_PI, 2 * M_PI);
  if (a <= 0) a += 2 * M_PI;
  return a - M_PI;
}

Controls Guidance::update(double t, const FlightState& x) {
  if (!p_.enabled() || t + 1e-12 < next_) return held_;
  const double dt = last_ < 0 ? 1.0 / p_.rate : t - last_;
  last_ = t;
  next_ = t + 1.0 / p_.rate;
  const Vec3 ground = x.attitude * x.velocity;  // NED
  // Pass waypoints that are near; the last is never passed.
  auto offset = [&](int i) {
    return Eigen::Vector2d(p_.waypoints[i][0] - x.position.x(), p_.waypoints[i][1] - x.position.y());
  };
  while (current_ + 1 < int(p_.waypoints.size()) && offset(current_).norm() < p_.acceptanceRadius) ++current_;
  const Eigen::Vector2d d = offset(current_);
  const double bearing = std::atan2(d.y(), d.x());
  const double course = std::atan2(ground.y(), ground.x());
  const double e = wrapAngle(bearing - course);
  courseIntegral_ = std::clamp(courseIntegral_ + e * dt, -p_.course.integralLimit, p_.course.integralLimit);
  const double de = wrapAngle(e - lastCourseError_) / dt;
  lastCourseError_ = e;
  const double command = std::clamp(p_.course.kp * e + p_.course.ki * courseIntegral_ + p_.course.kd * de,
                                    -p_.maxYawRate, p_.maxYawRate);
  // The heading's rate from the body rates (Euler kinematics): ψ' = (q sin φ + r cos φ) / cos θ.
  const Mat3 r = x.attitude.toRotationMatrix();
  const double phi = std::atan2(r(2, 1), r(2, 2)), theta = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  const double yawRate =
      (x.rates.y() * std::sin(phi) + x.rates.z() * std::cos(phi)) / std::max(0.1, std::cos(theta));
  const double re = command - yawRate;
  rateIntegral_ = std::clamp(rateIntegral_ + re * dt, -p_.yawRate.integralLimit, p_.yawRate.integralLimit);
  const double dre = (re - lastRateError_) / dt;
  lastRateError_ = re;
  const double brake = std::clamp(p_.yawRate.kp * re + p_.yawRate.ki * rateIntegral_ + p_.yawRate.kd * dre,
                                  -p_.maxBrake, p_.maxBrake);
  const bool pullRight = (brake >= 0) == p_.rightTurnPullsRight;
  held_ = pullRight ? Controls{0.0, std::abs(brake)} : Controls{std::abs(brake), 0.0};
  if (p_.glideSlope.enabled()) {
    // The glide path: from here over the waypoints still ahead to the target.
    double remaining = d.norm();
    for (std::size_t i = current_ + 1; i < p_.waypoints.size(); ++i)
      remaining += std::hypot(p_.waypoints[i][0] - p_.waypoints[i - 1][0],
                              p_.waypoints[i][1] - p_.waypoints[i - 1][1]);
    const double toDeg = 180.0 / M_PI;
    requiredGlide_ = std::atan2(std::max(0.0, -x.position.z()), remaining) * toDeg;
    const double flown = std::atan2(ground.z(), ground.head<2>().norm()) * toDeg;
    findGlideControl(p_.glideSlope.control)->apply(held_, glide_.update(dt, requiredGlide_, flown));
  }
  return held_;
}

}  // namespace fsi::flight
