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
  int threads = 1;  ///< threads an effect may use (effects/Threads.hpp); 1 = serial
};

class Effect {
 public:
  virtual ~Effect() = default;
  virtual std::string name() const = 0;
  virtual void addForces(ForceContext& ctx) const = 0;
};

struct Nodes;

/// Zeroes the node force arrays and lets every effect add its forces at the nodes' current state.
/// The returned context holds the smallest element stable step and (if asked) the strain energy.
ForceContext evaluateEffects(Nodes& nodes, const std::vector<const Effect*>& effects, double time,
                             double loadFactor, bool wantEnergy, int threads = 1);

}  // namespace fsi::structure
