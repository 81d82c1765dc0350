#pragma once
// ThreadedForces: the force assembler. It evaluates a list of effects, serially or on several threads
// (scene key solver.threads; docs/PERFORMANCE.md "Threads"), and owns everything about the parallelism:
// which effects split, the shares and node bands, the seam buffers, the barriers, and every effect's
// working memory (ForceContext::scratch). The effects only describe their items and the nodes each writes
// to (Effect::connectivity) and evaluate ranges of them (Effect::addRange, Effect::prepareRange).
//
// Every effect with items splits (the membrane and cable kernels, the pressure loads, gravity, the fabric's
// bending), except a scattered one (Connectivity::scattered: the cables) with fewer than kMinParallelItems
// items; a light one (Connectivity::light: gravity) splits but never decides the threading. Each is cut into
// as many contiguous item ranges as there are shares (on multiples of Connectivity::batch), one share per
// thread. An effect with first passes over all its items (Connectivity::prepass, prepasses: the bending's
// hinge angles, then its moments) has each of them split first, each followed by a barrier. The
// nodes are cut into as many bands, at the lowest node of each share's first element of the largest split
// effect: the elements are sorted by their lowest node and the nodes follow a Morton curve, so nearly all of
// a share's elements have every node in its own band. Those elements write straight into the node arrays,
// whose band the share clears first: no other thread writes there. The few elements that reach into another
// band (the seam: where the Morton curve folds back, a share boundary's neighbours) write into the share's
// own buffer, of which only the nodes they touch are cleared and added. So the forces cross memory once, as
// in a serial evaluation; a buffer per share over its whole node range (the first design) cost the
// 10⁶-triangle step a fifth more memory traffic and its 1.8× on 2 cores. The effects that do not split (line
// and body drag, nodal forces, small cable sets: a few hundred items) write anywhere: they run on the first
// thread after a barrier, into the node arrays, while the other threads wait (before, they ran after the
// first share's elements while the others waited: the same wall time, one barrier more; none when a scene has
// no such effect). Then, after a barrier, each thread adds the seam buffers into its band and moves its
// band's nodes. Nothing is locked. Only the order of the sums at seam nodes and of the energy sums differs
// from a serial evaluation (round-off). Colouring (groups of elements without a shared node) would need no
// buffer at all but break the batched kernel's contiguous runs of elements and the locality of the sorted
// order.
//
// The phases are separate calls so that the integrator can put them in ONE parallel region with its node
// sweep (CentralDifference::step: fork, forces, barrier, gather and sweep of the same band, join): each
// fork, join or barrier costs a thread wake-up, tens of µs on a virtual machine when the threads sleep
// (OMP_WAIT_POLICY=passive). evaluate() is a whole evaluation in its own region for everything else.
// Nothing is allocated after construction.

#include <memory>
#include <vector>

#include "structure/effects/Effect.hpp"

namespace fsi::structure {

struct Nodes;

class ThreadedForces {
 public:
  /// One share (serial: evaluateEffects with this object's scratch) if threads ≤ 1, without OpenMP, or when
  /// no split effect that is not light has kMinParallelItems items (effects/Threads.hpp). Reads every
  /// effect's connectivity once, here; allocates the effects' working memory.
  ThreadedForces(std::vector<const Effect*> effects, int threads, int nodes);

  int shares() const { return int(shares_.size()); }
  bool serial() const { return shares_.size() <= 1; }

  /// Phase 1, called by EVERY thread t of nt of a parallel region (it has barriers): thread t evaluates
  /// shares t, t + nt, ...: its part of the split effects' first passes (Effect::prepareRange; then a
  /// barrier), clears the share's band of base.fint and base.fext and its seam buffer, adds the forces of its
  /// elements of every split effect; then (after a barrier) thread 0 adds the effects that do not split.
  /// `base` gives x, v, the node arrays, time, load factor and wantEnergy. The caller puts a barrier after.
  void evaluateShares(int t, int nt, const ForceContext& base);
  /// Phase 2, after phase 1 and a barrier: adds the seam buffers into fint and fext over the band
  /// [nodeBegin(s), nodeEnd(s)).
  void gather(int s, double* fint, double* fext) const;
  int nodeBegin(int s) const { return shares_[std::size_t(s)].nodeBegin; }
  int nodeEnd(int s) const { return shares_[std::size_t(s)].nodeEnd; }
  /// Smallest stable step and strain energy of the last phase 1, over the shares in share order.
  double minStableDt() const;
  double strainEnergy() const;
  /// Elements (over all split effects) that write into a seam buffer, and all split elements.
  long seamElements() const;
  long splitElements() const;

  /// A whole evaluation (both phases, one parallel region): as evaluateEffects.
  ForceContext evaluate(Nodes& nodes, double time, double loadFactor, bool wantEnergy);

 private:
  /// Elements [begin, end) of split effect `effect`, into the node arrays (direct) or the seam buffer.
  struct Run {
    int effect = 0, begin = 0, end = 0;
    bool direct = true;
  };
  struct alignas(64) Share {
    std::vector<Run> runs;
    int nodeBegin = 0, nodeEnd = 0;        ///< its band: cleared and written directly, gathered and swept
    std::unique_ptr<double[]> fint, fext;  ///< seam buffer by dof: only the `touched` nodes' are set
    std::vector<int> touched;              ///< nodes the seam elements write to, ascending
    double dt = 0, energy = 0;             ///< its stable step and strain energy
  };
  void evaluateShare(int s, const ForceContext& base);
  void evaluateWhole(const ForceContext& base);
  /// An effect with its connectivity (read once, at construction) and its working memory.
  struct Part {
    const Effect* effect = nullptr;
    Connectivity items;
    double* scratch = nullptr;  ///< in scratch_
  };
  std::vector<const Effect*> effects_;
  EffectScratch scratch_;  ///< every effect's working memory (ForceContext::scratch), in effects_ order
  std::vector<Part> split_, whole_;
  int prepasses_ = 0;  ///< the most first passes over all its items of a split effect (Connectivity::prepass)
  std::vector<Share> shares_;
  double wholeDt_ = 0, wholeEnergy_ = 0;
};

}  // namespace fsi::structure
