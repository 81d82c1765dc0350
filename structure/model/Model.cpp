#include "structure/model/Model.hpp"

#include <fmt/format.h>

#include <cmath>

namespace fsi::structure {

double membraneWaveSpeed(const MembraneMaterial& m) {
  return std::sqrt(m.young / (m.density * (1.0 - m.poisson * m.poisson)));
}

std::string Model::describeNode(int node) const {
  return fmt::format("node {} of mesh '{}'", nodes.tag[node], meshes[nodes.mesh[node]].name);
}
std::string Model::describeTriangle(int e) const {
  return fmt::format("triangle {} of mesh '{}'", membranes.tag[e], meshes[membranes.mesh[e]].name);
}
std::string Model::describeCable(int e) const {
  return fmt::format("cable {} of mesh '{}'", cables.tag[e], meshes[cables.mesh[e]].name);
}

}  // namespace fsi::structure
