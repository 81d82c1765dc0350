#pragma once
// The `round_canopy` generator entry of a scene (meshes.NAME.generator with type: round_canopy): reads its
// keys into RoundCanopyParams through the generator's schema section (names, types, defaults, ranges:
// roundCanopySchema(), listed in docs/SCENES.md's key reference).

#include "structure/roundcanopy/RoundCanopyGeometry.hpp"
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure::roundcanopy {

/// The generator entry's keys: the one list the reader reads through and the docs are made from.
const SchemaSection& roundCanopySchema();

/// Reads the generator entry (all keys but `type` optional); errors are located at the key.
RoundCanopyParams readRoundCanopyParams(const YamlMap& entry);

}  // namespace fsi::structure::roundcanopy
