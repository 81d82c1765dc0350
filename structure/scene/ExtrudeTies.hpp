#pragma once
// The scene's `extrude` constraints: a 2D model built as a strip of elements one element wide along an
// extrusion direction. The nodes of the set with equal coordinates apart from the one along the direction
// (within a tolerance) form a tie group, which the integrators move as one across the direction
// (TieGroups in integrate/Constraints.hpp). Grouping and every check against the scene's other constraints
// are here, with errors located at the entry.

#include <array>
#include <vector>

#include "structure/integrate/Constraints.hpp"
#include "structure/model/Model.hpp"
#include "structure/model/SchemaKey.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure {

/// The keys of `constraints[i].extrude` (SceneSchema).
const SchemaSection& extrudeSchema();

/// One `- {nodes: SEL, extrude: {direction: d, tolerance: 1e-9, hold: false}}` entry, read but not resolved.
struct ExtrudeRequest {
  YamlMap entry;    ///< constraints[i]
  YamlMap extrude;  ///< constraints[i].extrude
  int index = 0;    ///< i
  std::vector<int> nodes;
  std::array<double, 3> direction{0, 0, 0};  ///< unit
  double tolerance = 1e-9;
  bool hold = false;
};

/// Which constraint entry (its index in `constraints:`, −1 for none) fixed each dof, prescribed each node or
/// put it on an oblique plane, for the checks and their messages.
struct ConstraintOrigins {
  std::vector<int> fixedBy;       ///< per dof
  std::vector<int> prescribedBy;  ///< per node
  std::vector<int> sliderBy;      ///< per node
};

/// Reads an entry with an `extrude` key (the caller has checked it has one).
ExtrudeRequest readExtrude(const YamlMap& entry, int index, std::vector<int> nodes);

/// Forms the tie groups of every request, checks them (partners within tolerance, a node in one group only,
/// no conflicting fix, prescribed motion or oblique plane) and adds them, and their `hold`, to `c`.
void addExtrudeTies(const std::vector<ExtrudeRequest>& requests, const Model& model,
                    const ConstraintOrigins& origins, Constraints& c);

}  // namespace fsi::structure
