#pragma once
// The scene's `coupling:` section: the triangles that receive the flow's pressure field (an effect like any
// other) and how the load is taken over a coupling window.

#include "structure/model/SchemaKey.hpp"
#include "structure/scene/Scene.hpp"
#include "structure/scene/SetResolver.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure {

/// The `coupling:` section's keys.
const SchemaSection& couplingSchema();

/// Adds the interface-pressure effect to `scene` when `top` has `coupling:`.
void readCoupling(const YamlMap& top, const SetResolver& sets, Scene& scene);

}  // namespace fsi::structure
