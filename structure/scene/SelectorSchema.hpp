#pragma once
// The declared forms of the scene's selectors and named sets (SceneSchema): the keys of each mapping form of
// a node selector (plane, box, nearest, ids), read by SetResolver, and the `sets` section. The name and list
// forms (`name`, `mesh/group`, `[sel, ...]`) and the triangle and line selectors have no keys; they are
// described in the sections' descriptions and in docs/SCENES.md, "Selectors".

#include "structure/model/SchemaKey.hpp"

namespace fsi::structure {

const SchemaSection& setsSchema();
const SchemaSection& planeSelectorSchema();
const SchemaSection& boxSelectorSchema();
const SchemaSection& nearestSelectorSchema();
const SchemaSection& idsSelectorSchema();

}  // namespace fsi::structure
