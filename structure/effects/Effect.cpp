#include "structure/effects/Effect.hpp"

#include <algorithm>

#include "structure/model/Model.hpp"

namespace fsi::structure {

void Connectivity::appendNodes(int item, std::vector<int>& out) const {
  if (offsets != nullptr) {
    out.insert(out.end(), nodes + offsets[item], nodes + offsets[item + 1]);
  } else if (nodes == nullptr) {
    out.push_back(item);
  } else {
    const int* first = nodes + long(nodesPerItem) * item;
    out.insert(out.end(), first, first + nodesPerItem);
  }
}

EffectScratch::EffectScratch(const std::vector<const Effect*>& effects) {
  buffers_.reserve(effects.size());
  for (const Effect* e : effects) {
    const std::size_t n = e->connectivity().scratch;
    buffers_.emplace_back(n > 0 ? new double[n]() : nullptr);
  }
}

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

ForceContext evaluateEffects(Nodes& nodes, const std::vector<const Effect*>& effects,
                             const EffectScratch& scratch, double time, double loadFactor, bool wantEnergy) {
  std::fill(nodes.fint.begin(), nodes.fint.end(), 0.0);
  std::fill(nodes.fext.begin(), nodes.fext.end(), 0.0);
  ForceContext ctx = forceContextFor(nodes, time, loadFactor, wantEnergy);
  for (std::size_t i = 0; i < effects.size(); ++i) {
    ctx.scratch = scratch.of(i);
    effects[i]->addForces(ctx);
  }
  ctx.scratch = nullptr;
  return ctx;
}

ForceContext evaluateEffects(Nodes& nodes, const std::vector<const Effect*>& effects, double time,
                             double loadFactor, bool wantEnergy) {
  const EffectScratch scratch(effects);
  return evaluateEffects(nodes, effects, scratch, time, loadFactor, wantEnergy);
}

}  // namespace fsi::structure
