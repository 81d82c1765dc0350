#pragma once
// Simulation: runs a Scene with the central-difference integrator and does everything around the step loop:
// output frames (HDF5 + XDMF), probes, energy monitoring, until-static detection, instability diagnosis with
// the last good state kept on disk, Ctrl-C handling, and summary.json.

#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "structure/scene/Scene.hpp"

namespace fsi::structure {

struct RunOptions {
  std::filesystem::path outDir;
  bool quiet = false;
  double progressSeconds = 2.0;  ///< wall time between progress lines
};

enum class StopReason { EndTime, Static, NotConverged, Unstable, Interrupted };
std::string toString(StopReason r);

struct RunResult {
  StopReason reason = StopReason::EndTime;
  std::map<std::string, double> probes;
  nlohmann::json summary;
  std::string diagnosis;  ///< non-empty when unstable
  int exitCode() const;
};

/// Evaluates every probe of the scene at the model's current state (forces must be current for reactions).
std::map<std::string, double> evaluateProbes(const Scene& scene);

/// Runs to the end (or static state, instability, interrupt); writes results into options.outDir.
RunResult runSimulation(Scene& scene, const RunOptions& options);

/// Installs a SIGINT handler that asks running simulations to stop cleanly.
void installInterruptHandler();

}  // namespace fsi::structure
