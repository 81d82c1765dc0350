#pragma once
// What the laplace probe (LaplaceProbe.cpp) needs of its nodes, for the scene's reader to check at load time.

#include <string>
#include <vector>

#include "structure/model/Model.hpp"

namespace fsi::structure {

/// Empty if the curvature fit works at `node` over `rings` rings of `triangles` (the node inside the surface
/// with at least 6 neighbours); else why not, naming the node.
std::string laplaceFitProblem(const Model& model, const std::vector<int>& triangles, int node, int rings);

}  // namespace fsi::structure
