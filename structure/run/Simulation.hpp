#pragma once
// Simulation: runs a Scene with the central-difference integrator and does everything around the step loop:
// output frames (HDF5 + XDMF), probes, energy monitoring, until-static detection, instability diagnosis with
// the last good state kept on disk, stop requests (RunOptions::stop), and summary.json; what it shares with
// the dynamic-relaxation run is in RunCommon.

#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "structure/integrate/StateSnapshot.hpp"
#include "structure/integrate/StopReason.hpp"
#include "structure/run/StopToken.hpp"
#include "structure/scene/Scene.hpp"

namespace fsi::structure {

struct RunOptions {
  std::filesystem::path outDir;
  bool quiet = false;
  double progressSeconds = 2.0;  ///< wall time between progress lines
  /// A request on it stops the run cleanly (honoured during set-up, at every step and every DR iteration);
  /// none: the run cannot be stopped from outside.
  const StopToken* stop = nullptr;
  /// Where the start state came from (`fsi run --start-from`), copied into summary.json as "start_from";
  /// null: the reference state.
  nlohmann::json startFrom;
  /// An explicit run continues from this state (time, step, dt, x, v of a state file: `fsi run --start-from
  /// interrupted_state.h5`) instead of starting at rest at time 0; its node count must be the model's.
  std::optional<StateSnapshot> startState;
  /// With startState: continue the series in outDir/results.h5 (its frames up to the state's time are kept,
  /// later ones dropped) instead of starting a new one at the state's time.
  bool continueSeries = false;
};

struct RunResult {
  StopReason reason = StopReason::EndTime;
  std::map<std::string, double> probes;
  nlohmann::json probeExtremes;  ///< RunOutput::extremes() of an explicit run (summary.json: probe_extremes)
  nlohmann::json summary;
  std::string diagnosis;            ///< what stopped the run (unstable, interrupted, not converged)
  std::filesystem::path stateFile;  ///< last_good_state.h5 / interrupted_state.h5 when one was written
  int stopSignal = 0;               ///< interrupted: the signal that asked for the stop (0: none)
  int exitCode() const { return structure::exitCode(reason, stopSignal); }
};

/// Evaluates every probe of the scene at the model's current state (forces must be current for reactions).
std::map<std::string, double> evaluateProbes(const Scene& scene);

/// Runs to the end (or static state, instability, a stop request); writes results into options.outDir.
RunResult runSimulation(Scene& scene, const RunOptions& options);

/// Dynamic relaxation of a `solver: {type: dynamic_relaxation}` scene (runSimulation dispatches to it).
RunResult runRelaxation(Scene& scene, const RunOptions& options);

}  // namespace fsi::structure
