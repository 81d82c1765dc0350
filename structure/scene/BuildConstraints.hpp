#pragma once
// The scene's `constraints:` list (fix, symmetry, prescribe, extrude) resolved against the model.

#include "structure/integrate/Constraints.hpp"
#include "structure/model/Model.hpp"
#include "structure/model/SchemaKey.hpp"
#include "structure/scene/SetResolver.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure {

/// The constraint entries' keys (fix, symmetry, prescribe; `extrude` is read by ExtrudeTies, not in the
/// schema yet).
const SchemaSection& fixSchema();
const SchemaSection& symmetrySchema();
const SchemaSection& prescribeSchema();

Constraints buildConstraints(const YamlMap& top, const Model& model, const SetResolver& sets);

}  // namespace fsi::structure
