#pragma once
// GlideControls: the registry of the controls the glide-slope loop (flight/GlideSlope) can fly with. Each
// kind says how one number, the loop's output, sets the Controls, its unit and its valid range; a flight file
// names one in `guidance.glide_slope.control`. A positive output steepens the glide on the tables of this
// project.

#include <string>
#include <vector>

#include "flight/FlightSystem.hpp"

namespace fsi::flight {

struct GlideControlKind {
  const char* name;
  const char* unit;        ///< of the output, trim, min and max in the flight file
  double lowest, highest;  ///< the range min and max must lie in
  double defaultMin, defaultMax;
  const char* description;
  void (*apply)(Controls& controls, double output);
};

/// Every kind, in the order of the documentation.
const std::vector<GlideControlKind>& glideControlKinds();
/// The kind of that name, or nullptr.
const GlideControlKind* findGlideControl(const std::string& name);

}  // namespace fsi::flight
