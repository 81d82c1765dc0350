#pragma once
// Readers of the scene sections that need no model: `solver:`, `time:` and `output:`.

#include "structure/model/SchemaKey.hpp"
#include "structure/scene/RunControls.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure {

/// The sections' declared keys (SceneSchema): what the readers below read through.
const SchemaSection& solverSchema();
const SchemaSection& relaxationSchema();  ///< `solver:` with `type: dynamic_relaxation`
const SchemaSection& timeSchema();
const SchemaSection& untilStaticSchema();
const SchemaSection& outputSchema();

/// `solver:` (absent = explicit dynamics).
SolverControl readSolver(const YamlMap& top);

/// `time:`. A dynamic-relaxation scene has none; a coupled scene (`coupling:`) may leave the end open.
TimeControl readTime(const YamlMap& top, bool relaxation);

/// `output:` (absent = every field, first and last frame).
OutputControl readOutput(const YamlMap& top);

}  // namespace fsi::structure
