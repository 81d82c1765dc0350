#pragma once
// The scene's `constraints:` list (fix, symmetry, prescribe, extrude) resolved against the model.

#include "structure/integrate/Constraints.hpp"
#include "structure/model/Model.hpp"
#include "structure/scene/SetResolver.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure {

Constraints buildConstraints(const YamlMap& top, const Model& model, const SetResolver& sets);

}  // namespace fsi::structure
