#pragma once
// One evaluation of a model's membrane forces through a given MembraneForces (kernel and damping chosen by
// the caller), for the tests that compare two ways of computing the same forces: the batched against the
// per-element kernel (test_membrane_batch.cpp), threaded against serial (test_threads.cpp).
#include <algorithm>
#include <limits>
#include <vector>

#include "structure/effects/ThreadedForces.hpp"
#include "structure/elements/MembraneForces.hpp"
#include "structure/model/Model.hpp"

namespace fsi::structure::test {

struct MembraneEvaluation {
  std::vector<double> f;  ///< internal forces, 3 per node
  double energy = 0, dt = 0;
  int shares = 1;  ///< element shares the evaluation was split into (1: serial)
};

inline MembraneEvaluation evaluateMembranes(const Model& m, const MembraneForces& mf, int threads = 1,
                                            double dtStart = std::numeric_limits<double>::infinity()) {
  MembraneEvaluation r;
  if (threads > 1) {  // through the solver's threaded evaluation, on a copy of the nodes
    Nodes n = m.nodes;
    ThreadedForces tf({&mf}, threads, n.count);
    const ForceContext ctx = tf.evaluate(n, 0.0, 1.0, true);
    r.f = n.fint;
    r.energy = ctx.strainEnergy;
    r.dt = std::min(dtStart, ctx.minStableDt);
    r.shares = tf.shares();
    return r;
  }
  r.f.assign(3 * m.nodes.count, 0.0);
  std::vector<double> fext(r.f.size(), 0.0);
  ForceContext ctx;
  ctx.x = m.nodes.x.data();
  ctx.v = m.nodes.v.data();
  ctx.fint = r.f.data();
  ctx.fext = fext.data();
  ctx.wantEnergy = true;
  ctx.minStableDt = dtStart;
  mf.addForces(ctx);
  r.energy = ctx.strainEnergy;
  r.dt = ctx.minStableDt;
  return r;
}

}  // namespace fsi::structure::test
