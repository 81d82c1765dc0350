#include "flight/GlideControls.hpp"

#include <algorithm>
#include <cmath>

namespace fsi::flight {

const std::vector<GlideControlKind>& glideControlKinds() {
  static const std::vector<GlideControlKind> kinds = {
      {"incidence", "deg", -30, 30, -5, 5,
       "the rigging's change (Controls::incidence): the canopy point turned about the mass centre",
       [](Controls& c, double u) { c.incidence = u * M_PI / 180.0; }},
      {"symmetric_brake", "fraction of the full travel", 0, 1, 0, 1,
       "both brakes pulled by the output on top of the differential brake of the heading loop (at most 1)",
       [](Controls& c, double u) {
         c.brakeLeft = std::min(1.0, c.brakeLeft + u);
         c.brakeRight = std::min(1.0, c.brakeRight + u);
       }},
  };
  return kinds;
}

const GlideControlKind* findGlideControl(const std::string& name) {
  for (const GlideControlKind& k : glideControlKinds())
    if (name == k.name) return &k;
  return nullptr;
}

}  // namespace fsi::flight
