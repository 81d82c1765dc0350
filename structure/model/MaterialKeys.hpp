#pragma once
// The keys of the scene's material entries (`materials.NAME`, one section per material type) with their
// ranges, declared once: the scene reader reads through these sections (scene/MaterialTypes, a located
// message at the key) and the model builder checks a material it is given with the same entries and the same
// message (checkMaterial), so a range is written in one place.

#include "structure/model/Materials.hpp"
#include "structure/model/SchemaKey.hpp"

namespace fsi::structure {

const SchemaSection& membraneMaterialKeys();
const SchemaSection& cableMaterialKeys();
const SchemaSection& pointMassMaterialKeys();

/// Throws an InputError "material 'NAME': KEY is V; valid: RANGE" for the first value out of its key's
/// range (the message of the key's entry, SceneKey::rangeMessage).
void checkMaterial(const MembraneMaterial& m);
void checkMaterial(const CableMaterial& m);
void checkMaterial(const PointMassMaterial& m);

}  // namespace fsi::structure
