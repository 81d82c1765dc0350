#include "structure/effects/Effect.hpp"

#include <algorithm>

#include "structure/model/Model.hpp"

namespace fsi::structure {

ForceContext evaluateEffects(Nodes& nodes, const std::vector<const Effect*>& effects, double time,
                             double loadFactor, bool wantEnergy, int threads) {
  std::fill(nodes.fint.begin(), nodes.fint.end(), 0.0);
  std::fill(nodes.fext.begin(), nodes.fext.end(), 0.0);
  ForceContext ctx;
  ctx.time = time;
  ctx.loadFactor = loadFactor;
  ctx.x = nodes.x.data();
  ctx.v = nodes.v.data();
  ctx.fint = nodes.fint.data();
  ctx.fext = nodes.fext.data();
  ctx.wantEnergy = wantEnergy;
  ctx.threads = threads;
  for (const Effect* e : effects) e->addForces(ctx);
  return ctx;
}

}  // namespace fsi::structure
