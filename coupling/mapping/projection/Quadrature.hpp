#pragma once
// The target quadrature of the L2 projection: the edge-midpoint rule on the level² sub-triangles of every
// target fan triangle, each point once with its summed weight (coupling/mapping/L2Projection).

#include <array>
#include <utility>
#include <vector>

#include "coupling/interface/SurfaceSearch.hpp"

namespace fsi::coupling {

// A target quadrature point: barycentric point of a target fan triangle and its (summed) weight.
struct QuadPoint {
  int triangle;
  std::array<double, 3> bary;
  double weight;
};

// Edge-midpoint rule on the level² sub-triangles of every target fan triangle. The rule's points are the
// lattice points (I, J, K)/(2 level), I + J + K = 2 level, with exactly two odd coordinates; a point on a fan
// triangle's edge is shared with the neighbour across that edge, so it is created once (by the first
// triangle) and its weights summed, which halves the searches for level 1.
// With `perTriangle`, also records every triangle's own (point, weight) pairs, 3 level (level + 1) / 2 per
// triangle in triangle order, for test functions that are discontinuous between faces.
std::vector<QuadPoint> quadraturePoints(const FanTriangulation& fan, int level,
                                        std::vector<std::pair<int, double>>* perTriangle);

}  // namespace fsi::coupling
