#pragma once
// StateSnapshot: the structure's state at one instant, the one type for every kept state: the integrator's
// checkpoints (CentralDifference::checkpoint / restore: implicit coupling repeats a window from one, a run
// returns to its last good state), the best iterate of a dynamic relaxation (DynamicRelaxation::best), and
// restart / stop state files (io/StateFile, which stores time, step, dt, x, v, scalars and arrays).

#include <map>
#include <string>
#include <vector>

#include "structure/integrate/EnergyLedger.hpp"

namespace fsi::structure {

struct StateSnapshot {
  double time = 0;  ///< simulated time; for a relaxation: the load factor
  long step = 0;    ///< steps taken; for a relaxation: the iteration
  double dt = 0;    ///< last step Δt(n) (0 before the first); for a relaxation: 1
  std::vector<double> x,
      v;  ///< positions and velocities (v(n−½) for central differences), 3N, xyz interleaved
  /// Central differences' bookkeeping and element step estimate at this state, so that a restored run goes on
  /// exactly as the original did. In memory only: a state file keeps what its writer puts in `scalars` and
  /// `arrays`.
  EnergyLedger ledger;
  double stableDt = 0;
  std::map<std::string, double> scalars;              ///< energies, residual ratio, etc.
  std::map<std::string, std::vector<double>> arrays;  ///< any further per-entity state

  /// No state kept (a default snapshot).
  bool empty() const { return x.empty(); }
};

}  // namespace fsi::structure
