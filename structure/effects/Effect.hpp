#pragma once
// Effect: one physical contribution to the nodal forces (membrane stress, cable tension, follower pressure,
// gravity, ...). A scene lists the effects it wants; the integrator holds exactly those, so a disabled effect
// is never visited in the step loop. Effects with elements also bound the stable time step.

#include <limits>
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
};

class Effect {
 public:
  virtual ~Effect() = default;
  virtual std::string name() const = 0;
  virtual void addForces(ForceContext& ctx) const = 0;

  // Effects whose elements can be evaluated in contiguous ranges on separate threads (ThreadedForces.hpp).
  // An effect that does not split runs whole on the first thread, while the others wait.
  /// Elements to split; 0: the effect does not split.
  virtual int splitItems() const { return 0; }
  /// Whether this effect's elements alone can be worth threads (ThreadedForces threads an evaluation only
  /// when such an effect has kMinParallelItems elements): false for a pass as cheap as gravity's m g per
  /// node, which splits when something else is threaded but never decides it.
  virtual bool splitDecides() const { return true; }
  /// Share boundaries fall on multiples of this (a batched kernel's batch width).
  virtual int splitAlignment() const { return 1; }
  /// Appends the nodes that element `element` writes forces to (with repeats, in any order).
  virtual void splitElementNodes(int /*element*/, std::vector<int>& /*nodes*/) const {}
  /// The forces of elements [begin, end) (and their stable step and strain energy) into ctx: addForces()
  /// is addRange(ctx, 0, splitItems()). The ranges of one evaluation tile [0, splitItems()) and each writes
  /// only to the nodes its elements name (splitElementNodes): the caller may send each range's forces into
  /// different arrays.
  virtual void addRange(ForceContext& /*ctx*/, int /*begin*/, int /*end*/) const {}
  /// A per-item pass that every range's addRange needs done for ALL items first (e.g. the bending's hinge
  /// angles, which each triangle's curvature reads): items [begin, end) at ctx.x into the effect's own
  /// scratch, no node forces. ThreadedForces splits it over the threads, then waits at a barrier; addForces()
  /// does that work for all items itself before its elements. 0: none.
  virtual int prepareItems() const { return 0; }
  virtual void prepareRange(const ForceContext& /*ctx*/, int /*begin*/, int /*end*/) const {}
};

/// Appends conn[k * element, k * element + k) (k nodes per element) to nodes.
void appendElementNodes(const std::vector<int>& conn, int k, int element, std::vector<int>& nodes);

struct Nodes;

/// A context pointing at the nodes' state and force arrays (the forces are not touched).
ForceContext forceContextFor(Nodes& nodes, double time, double loadFactor, bool wantEnergy);

/// Zeroes the node force arrays and lets every effect add its forces at the nodes' current state.
/// The returned context holds the smallest element stable step and (if asked) the strain energy. One thread;
/// ThreadedForces evaluates the same on several.
ForceContext evaluateEffects(Nodes& nodes, const std::vector<const Effect*>& effects, double time,
                             double loadFactor, bool wantEnergy);

}  // namespace fsi::structure
