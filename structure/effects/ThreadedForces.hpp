#pragma once
// ThreadedForces: one force evaluation on several threads (scene key solver.threads; docs/PERFORMANCE.md
// "Threads").
//
// Every effect that splits (Effect::splitItems: the membrane kernel, the pressure loads, the cable kernel
// from kMinParallelItems cables on) is cut into as many contiguous element ranges as there are shares, one
// share per thread. Share s evaluates its range of every split effect into its own force buffers; share 0
// writes straight into the node arrays, which it clears first, and also runs the effects that do not split.
// The elements are sorted by their lowest node and the nodes follow a Morton curve, so a share's elements
// touch a narrow band of nodes, which is all its buffers clear and hold. Then, after a barrier, each thread
// adds the buffers into the node arrays over its own range of nodes: no address is written by two threads and
// nothing is locked. Only the order of the sums at the nodes where two shares meet, and of the energy sums,
// differs from a serial evaluation (round-off). Colouring (groups of elements without a shared node) would
// save the buffers but break the batched kernel's contiguous runs of elements and the locality of the sorted
// order.
//
// The two phases are separate calls so that the integrator can put them in ONE parallel region with its node
// sweep (CentralDifference::step: fork, forces, barrier, gather and sweep of the same nodes, join): each
// fork, join or barrier costs a thread wake-up, tens of µs on a virtual machine when the threads sleep
// (OMP_WAIT_POLICY=passive). evaluate() is a whole evaluation in its own region for everything else.
// Nothing is allocated after construction.

#include <vector>

#include "structure/effects/Effect.hpp"

namespace fsi::structure {

struct Nodes;

class ThreadedForces {
 public:
  /// One share (serial: evaluateEffects) if threads ≤ 1, without OpenMP, or when no split effect has
  /// kMinParallelItems elements (effects/Threads.hpp).
  ThreadedForces(std::vector<const Effect*> effects, int threads, int nodes);

  int shares() const { return int(shares_.size()); }
  bool serial() const { return shares_.size() <= 1; }

  /// Phase 1 of share s (one call per share, any thread): clears its force buffers (share 0: base.fint and
  /// base.fext, whole) and adds the forces of its elements of every split effect (share 0: and of the
  /// effects that do not split). `base` gives x, v, the node arrays, time, load factor and wantEnergy.
  void evaluateShare(int s, const ForceContext& base);
  /// Phase 2, after every share's phase 1: adds the buffers into fint and fext over the nodes
  /// [nodeBegin(s), nodeEnd(s)).
  void gather(int s, double* fint, double* fext) const;
  int nodeBegin(int s) const { return shares_[std::size_t(s)].nodeBegin; }
  int nodeEnd(int s) const { return shares_[std::size_t(s)].nodeEnd; }
  /// Smallest stable step and strain energy of the last phase 1, over the shares in share order.
  double minStableDt() const;
  double strainEnergy() const;

  /// A whole evaluation (both phases, one parallel region): as evaluateEffects.
  ForceContext evaluate(Nodes& nodes, double time, double loadFactor, bool wantEnergy);

 private:
  struct Range {
    int begin = 0, end = 0;
  };
  struct alignas(64) Share {
    std::vector<Range> ranges;       ///< elements of each split effect
    int lo = 0, hi = 0;              ///< dofs the share's elements write to
    int nodeBegin = 0, nodeEnd = 0;  ///< nodes whose sums the share's thread gathers (phase 2)
    std::vector<double> fint, fext;  ///< the share's forces (dofs [lo, hi) used; unused by share 0)
    double dt = 0, energy = 0;       ///< its stable step and strain energy
  };
  std::vector<const Effect*> effects_;
  std::vector<const Effect*> split_, whole_;
  int nodes_ = 0;
  std::vector<Share> shares_;
};

}  // namespace fsi::structure
