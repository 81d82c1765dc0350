#pragma once
// Effect: one physical contribution to the nodal forces (membrane stress, cable tension, follower pressure,
// gravity, ...). A scene lists the effects it wants; the integrator holds exactly those, so a disabled effect
// is never visited in the step loop. Effects with elements also bound the stable time step.
//
// An effect knows its physics and its connectivity, nothing about threads: it says which items its forces
// are a sum over and which nodes each item writes to (connectivity()), and evaluates any range of them
// (addRange). Whoever evaluates (ThreadedForces: the partition into shares and node bands, the seam
// buffers, the barriers, the thread team; evaluateEffects) owns the parallelism and the working memory.
// An effect keeps no state across or during an evaluation: it may be evaluated by several assemblers.

#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace fsi::structure {

/// What one force evaluation needs and produces. Arrays are 3 per node, xyz interleaved.
struct ForceContext {
  double time = 0;
  double loadFactor = 1.0;    ///< scales every external load (incremental loading in static solvers)
  const double* x = nullptr;  ///< current coordinates
  const double* v = nullptr;  ///< velocities (half step behind in central differences)
  double* fint = nullptr;     ///< internal resisting forces (accumulated)
  double* fext = nullptr;     ///< external applied forces (accumulated)
  bool wantEnergy = false;    ///< also sum the strain energy (only on monitoring steps)
  double minStableDt = std::numeric_limits<double>::infinity();  ///< reduced by every element effect
  double strainEnergy = 0;                                       ///< accumulated when wantEnergy
  /// The evaluated effect's working memory, Connectivity::scratch doubles (null when it needs none),
  /// owned by the caller and shared by all ranges of one evaluation: the ranges of the first pass
  /// (prepareRange) and of the forces (addRange) each write only their own items' part of it.
  double* scratch = nullptr;
  int pass = 0;  ///< in prepareRange: which of the effect's first passes (Connectivity::prepasses)
};

/// Which items an effect's forces are a sum over (triangles, cables, hinges, nodes) and which nodes each
/// writes to; what its kernel needs of a range. The pointers view the effect's own arrays (valid while it
/// lives). An assembler cuts an evaluation into contiguous ranges of items from this alone.
struct Connectivity {
  int items = 0;                 ///< 0: one indivisible pass (addForces)
  int nodesPerItem = 1;          ///< item i writes to nodes[k i, k i + k), k = nodesPerItem
  const int* nodes = nullptr;    ///< model node numbers; null with k = 1: item i writes node i alone
  const int* offsets = nullptr;  ///< if set, instead of k: item i writes nodes[offsets[i], offsets[i + 1])
  int batch = 1;  ///< the kernel takes items in batches this wide: ranges (of both passes) start at multiples
  /// A few flops per item (gravity's m g): however many items, not worth waking threads for on its own.
  bool light = false;
  /// A small set of these items reaches across the node numbering (lines from a canopy to a confluence
  /// point): evaluated whole unless there are enough items to be worth threads on their own.
  bool scattered = false;
  /// prepareRange must have covered EVERY item before any addRange (each item's forces read a per-item
  /// result of others, e.g. the bending's hinge angles).
  bool prepass = false;
  /// With prepass: how many first passes, each covering every item before the next (the bending: the
  /// angles, then the moments), before any addRange.
  int prepasses = 1;
  std::size_t scratch = 0;  ///< doubles of ForceContext::scratch its passes need

  /// Appends the nodes item `item` writes to (with repeats, in any order).
  void appendNodes(int item, std::vector<int>& out) const;
};

class Effect {
 public:
  virtual ~Effect() = default;
  virtual std::string name() const = 0;
  /// All its forces (every item, or its one pass) into ctx, with its stable step and (if asked) strain
  /// energy. ctx.scratch must hold connectivity().scratch doubles.
  virtual void addForces(ForceContext& ctx) const = 0;
  /// Its items and the nodes each writes to; the default: no items (only addForces).
  virtual Connectivity connectivity() const { return {}; }
  /// The forces of items [begin, end) (and their stable step and strain energy), written only to the nodes
  /// those items name. The ranges of one evaluation tile [0, items); a caller may send each range's forces
  /// into different arrays. With a prepass, after prepareRange has covered every item.
  virtual void addRange(ForceContext& /*ctx*/, int /*begin*/, int /*end*/) const {}
  /// First pass ctx.pass of items [begin, end) at ctx.x into ctx.scratch (Connectivity::prepass); no forces.
  virtual void prepareRange(const ForceContext& /*ctx*/, int /*begin*/, int /*end*/) const {}
};

/// Working memory for the effects of a list: one buffer of connectivity().scratch doubles per effect.
class EffectScratch {
 public:
  explicit EffectScratch(const std::vector<const Effect*>& effects);
  /// The buffer of effect i of the list (null if it needs none).
  double* of(std::size_t i) const { return buffers_[i].get(); }

 private:
  std::vector<std::unique_ptr<double[]>> buffers_;
};

struct Nodes;

/// A context pointing at the nodes' state and force arrays (the forces are not touched).
ForceContext forceContextFor(Nodes& nodes, double time, double loadFactor, bool wantEnergy);

/// Zeroes the node force arrays and lets every effect add its forces (addForces, in list order, with the
/// effect's buffer of `scratch`) at the nodes' current state. The returned context holds the smallest
/// element stable step and (if asked) the strain energy. One thread; ThreadedForces evaluates the same on
/// several.
ForceContext evaluateEffects(Nodes& nodes, const std::vector<const Effect*>& effects,
                             const EffectScratch& scratch, double time, double loadFactor, bool wantEnergy);
/// The same with working memory of its own, allocated for this call: for one-off evaluations (the
/// integrators hold theirs in ThreadedForces).
ForceContext evaluateEffects(Nodes& nodes, const std::vector<const Effect*>& effects, double time,
                             double loadFactor, bool wantEnergy);

}  // namespace fsi::structure
