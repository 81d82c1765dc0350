#pragma once
// The `function:` key of loads and prescribed motions: a number or {type: constant | ramp | smooth_step |
// table | sine, ...}. Absent = constant 1.

#include <string>
#include <vector>

#include "structure/effects/TimeFunction.hpp"
#include "structure/model/SchemaKey.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure {

/// The time functions' sections (constant, ramp | smooth_step, sine, table), for the schema's docs.
const std::vector<const SchemaSection*>& timeFunctionSchemas();

TimeFunction readTimeFunction(const YamlMap& parent, const std::string& key);

}  // namespace fsi::structure
