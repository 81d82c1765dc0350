#pragma once
// Wind: the air's velocity over the ground, in world axes (NED) [m/s], as a function of altitude and time:
// a steady part, a linear shear with altitude (zero at the ground) and a (1 − cos) gust of given peak,
// start and duration — the three shapes of a flight-dynamics test.

#include "flight/Vec.hpp"

namespace fsi::flight {

struct Wind {
  Vec3 steady = Vec3::Zero();  ///< [m/s] (a wind from the east is (0, −V, 0): it blows towards the west)
  Vec3 shearPerMetre = Vec3::Zero();       ///< added per metre of altitude [1/s]
  Vec3 gustPeak = Vec3::Zero();            ///< [m/s]
  double gustStart = 0, gustDuration = 0;  ///< [s]; no gust when the duration is 0

  Vec3 at(const Vec3& positionNed, double time) const;
};

}  // namespace fsi::flight
