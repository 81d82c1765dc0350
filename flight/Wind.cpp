#include "flight/Wind.hpp"

#include <cmath>

namespace fsi::flight {

Vec3 Wind::at(const Vec3& positionNed, double time) const {
  const double altitude = std::max(0.0, -positionNed.z());
  Vec3 w = steady + shearPerMetre * altitude;
  if (gustDuration > 0 && time > gustStart && time < gustStart + gustDuration) {
    const double s = (time - gustStart) / gustDuration;
    w += gustPeak * 0.5 * (1.0 - std::cos(2.0 * M_PI * s));
  }
  return w;
}

}  // namespace fsi::flight
