// folds: how many interior edges of a triangle set (edges shared by exactly two of its triangles) have turned
// by more than `angle` degrees from their reference dihedral angle: creases of a membrane folded over at the
// scale of its elements, which a fluid mesh moved with it cannot follow (docs/RAMAIR.md). Measured against
// the reference, so a sharp edge of the design shape (a trailing edge) is no fold.
#include <fmt/format.h>

#include <cmath>

#include "structure/effects/FabricBending.hpp"
#include "structure/probes/ProbeKinds.hpp"

namespace fsi::structure {

namespace {

constexpr double kPi = 3.14159265358979323846;
void evaluate(const ProbeSpec& p, ProbeState& state, std::vector<double>& vals) {
  const Nodes& N = state.model().nodes;
  const double limit = p.angle * kPi / 180.0;
  int folds = 0;
  for (std::size_t h = 0; h + 3 < p.nodes.size(); h += 4) {
    const int* n = &p.nodes[h];
    const double now = hingeAngle(&N.x[3 * n[0]], &N.x[3 * n[1]], &N.x[3 * n[2]], &N.x[3 * n[3]], nullptr);
    const double ref = hingeAngle(&N.X[3 * n[0]], &N.X[3 * n[1]], &N.X[3 * n[2]], &N.X[3 * n[3]], nullptr);
    double d = std::abs(now - ref);
    if (d > kPi) d = 2 * kPi - d;
    if (d > limit) ++folds;
  }
  vals.push_back(double(folds));
}

}  // namespace

ProbeKind foldsProbe() {
  return {"folds",
          "interior edges of triangles turned by more than `angle` degrees from the reference (element-scale "
          "creases)",
          evaluate};
}

}  // namespace fsi::structure
