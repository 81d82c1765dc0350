// volume: the volume a set of triangles encloses about `center` (divergence theorem).
#include "structure/probes/ProbeKinds.hpp"

namespace fsi::structure {

namespace {

void evaluate(const ProbeSpec& p, ProbeState& state, std::vector<double>& vals) {
  const Model& model = state.model();
  const Nodes& N = model.nodes;
  // Divergence theorem about `center`: symmetry planes through the centre add nothing.
  double v = 0;
  for (int e : p.triangles) {
    const int* c = &model.membranes.conn[3 * e];
    double a[3], b[3], d[3];
    for (int k = 0; k < 3; ++k) {
      a[k] = N.x[3 * c[0] + k] - p.center[k];
      b[k] = N.x[3 * c[1] + k] - p.center[k];
      d[k] = N.x[3 * c[2] + k] - p.center[k];
    }
    v += a[0] * (b[1] * d[2] - b[2] * d[1]) + a[1] * (b[2] * d[0] - b[0] * d[2]) +
         a[2] * (b[0] * d[1] - b[1] * d[0]);
  }
  vals.push_back(v / 6.0);
}

}  // namespace

ProbeKind volumeProbe() {
  return {"volume", "the volume enclosed by a set of triangles about a centre", evaluate};
}

}  // namespace fsi::structure
