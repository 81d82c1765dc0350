#include "structure/effects/Effect.hpp"

#include <algorithm>

#include "structure/model/Model.hpp"

namespace fsi::structure {

ForceContext forceContextFor(Nodes& nodes, double time, double loadFactor, bool wantEnergy) {
  ForceContext ctx;
  ctx.time = time;
  ctx.loadFactor = loadFactor;
  ctx.x = nodes.x.data();
  ctx.v = nodes.v.data();
  ctx.fint = nodes.fint.data();
  ctx.fext = nodes.fext.data();
  ctx.wantEnergy = wantEnergy;
  return ctx;
}

ForceContext evaluateEffects(Nodes& nodes, const std::vector<const Effect*>& effects, double time,
                             double loadFactor, bool wantEnergy) {
  std::fill(nodes.fint.begin(), nodes.fint.end(), 0.0);
  std::fill(nodes.fext.begin(), nodes.fext.end(), 0.0);
  ForceContext ctx = forceContextFor(nodes, time, loadFactor, wantEnergy);
  for (const Effect* e : effects) e->addForces(ctx);
  return ctx;
}

void appendElementNodes(const std::vector<int>& conn, int k, int element, std::vector<int>& nodes) {
  const auto first = conn.begin() + long(k) * element;
  nodes.insert(nodes.end(), first, first + k);
}

}  // namespace fsi::structure
