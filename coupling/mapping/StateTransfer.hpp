#pragma once
// StateTransfer: a model's start state interpolated from another run's result on a mesh of the same geometry
// or the same resolution (`fsi run --start-from`): a relaxation continued in a load or resumed. (As a coarse
// start for a fine relaxation it does not pay: the interpolated state rings at element scale,
// docs/PERFORMANCE.md.)
//
// Each target node takes the source displacement at its closest point in the source's reference geometry:
//   - a node of a membrane triangle: on the source's triangles, preferring the closest triangle that faces
//   the
//     way the node's own triangles face (a thin wedge's two skins are closer to each other than a coarse
//     facet's sag), linear on that triangle;
//   - a node only on cables: on the source's cable segments, linear along the segment;
//   - any other node: the nearest source node.
// The displacement field is reproduced exactly where it is linear on the source's elements and the target's
// nodes lie on them.

#include <string>
#include <vector>

#include "structure/io/ResultsWriter.hpp"
#include "structure/model/Model.hpp"

namespace fsi::coupling {

struct StateTransferReport {
  int membraneNodes = 0;       ///< mapped onto the source's triangles
  int cableNodes = 0;          ///< mapped onto the source's cable segments
  int pointNodes = 0;          ///< took the nearest source node
  double largestDistance = 0;  ///< between a target node and its source point, reference geometry [m]
  int farthestNode = -1;       ///< the model node at that distance
};

/// Displacement (3 per node of `target`, at its reference coordinates X) interpolated from `source`.
/// `maxDistance` is the largest distance a node may have from the source's geometry; < 0 chooses 5 % of the
/// source's bounding-box diagonal. A farther node, or a source without the elements a node needs, throws
/// fsi::InputError naming `sourceName`, the node (its tag) and the distance.
std::vector<double> transferDisplacement(const structure::ResultsFrame& source,
                                         const structure::Model& target, const std::string& sourceName,
                                         double maxDistance = -1.0, StateTransferReport* report = nullptr);

}  // namespace fsi::coupling
