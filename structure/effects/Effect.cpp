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

void nodeSpanOf(const std::vector<int>& conn, int k, int begin, int end, int& lo, int& hi) {
  lo = hi = 0;
  if (begin >= end) return;
  const auto [mn, mx] = std::minmax_element(conn.begin() + long(k) * begin, conn.begin() + long(k) * end);
  lo = *mn;
  hi = *mx + 1;
}

}  // namespace fsi::structure
