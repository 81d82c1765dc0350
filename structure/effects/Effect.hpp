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
  // An effect that does not split runs whole on the first share's thread.
  /// Elements to split; 0: the effect does not split.
  virtual int splitItems() const { return 0; }
  /// Share boundaries fall on multiples of this (a batched kernel's batch width).
  virtual int splitAlignment() const { return 1; }
  /// Lowest node and one past the highest node that elements [begin, end) write to ({0, 0} if none).
  virtual void splitNodeSpan(int /*begin*/, int /*end*/, int& lo, int& hi) const { lo = hi = 0; }
  /// The forces of elements [begin, end) (and their stable step and strain energy) into ctx: addForces()
  /// is addRange(ctx, 0, splitItems()). Of the ranges of one evaluation only the first starts at 0, and its
  /// ctx holds the node arrays themselves: an effect may add a part that is not per element there.
  virtual void addRange(ForceContext& /*ctx*/, int /*begin*/, int /*end*/) const {}
};

/// Lowest node and one past the highest node in conn[k * begin, k * end) (k nodes per element).
void nodeSpanOf(const std::vector<int>& conn, int k, int begin, int end, int& lo, int& hi);

struct Nodes;

/// A context pointing at the nodes' state and force arrays (the forces are not touched).
ForceContext forceContextFor(Nodes& nodes, double time, double loadFactor, bool wantEnergy);

/// Zeroes the node force arrays and lets every effect add its forces at the nodes' current state.
/// The returned context holds the smallest element stable step and (if asked) the strain energy. One thread;
/// ThreadedForces evaluates the same on several.
ForceContext evaluateEffects(Nodes& nodes, const std::vector<const Effect*>& effects, double time,
                             double loadFactor, bool wantEnergy);

}  // namespace fsi::structure
