#pragma once
// The `function:` key of loads and prescribed motions: a number or {type: constant | ramp | smooth_step |
// table | sine, ...}. Absent = constant 1.

#include <string>

#include "structure/effects/TimeFunction.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure {

TimeFunction readTimeFunction(const YamlMap& parent, const std::string& key);

}  // namespace fsi::structure
