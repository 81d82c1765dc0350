#pragma once
// What the explicit run (Simulation.cpp) and the dynamic-relaxation run (RelaxationRun.cpp) share around
// their own loops: the stop request, the terminal lines (scene line, throttled progress), the output series
// (frames, probes table, further tables), the stop handling (the state a stopped run keeps on disk:
// last_good_state.h5 after an instability, interrupted_state.h5 after a stop request) and the end of a run
// (summary.json, stop line, probes and diagnosis on the terminal).

#include <chrono>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "structure/integrate/StateSnapshot.hpp"
#include "structure/io/SceneFrames.hpp"
#include "structure/run/Simulation.hpp"

namespace fsi::structure {

/// True once a stop was requested on the run's token (never cleared by a run).
inline bool stopRequested(const RunOptions& opt) {
  return opt.stop != nullptr && opt.stop->requested();
}

/// "SIGINT", "SIGTERM" (else "signal N"): how the summary and the terminal name a stop signal.
std::string signalName(int signal);

/// "scene FILE  (title)", the first line of every run on the terminal.
void printSceneLine(const Scene& scene);

/// "1200 nodes, 2000 membrane triangles, 40 cables, 6 bars": the nodes and every element kind the model has,
/// for the run log's model line.
std::string modelCounts(const Model& model);

/// Every element kind in summary.json: `<kind>_elements` (its count) for each, and under `element_kinds`
/// the count and the kind's report (ElementKind::report at configuration x) of each kind the model has.
void addElementKindStats(const Model& model, const double* x, nlohmann::json& stats);

/// The wall clock of a run and the throttle of its progress lines.
class RunClock {
 public:
  explicit RunClock(double progressSeconds);
  /// Wall seconds since the run started.
  double seconds() const;
  /// True if a progress line is due: progressSeconds after the last one, or a fiftieth of that if `soon`
  /// (a line per output frame of a short run). Counts the line as printed.
  bool progressDue(bool soon);

 private:
  using Clock = std::chrono::steady_clock;
  double progressSeconds_;
  Clock::time_point start_, lastPrint_;
};

/// The output series of a run in DIR/results.h5 (+ results.xdmf): the frames, from the initial one, and the
/// probes table (time and every probe, a row per recorded output).
class RunOutput {
 public:
  /// Creates the series and writes the initial frame (time 0, step 0; a continued run's: the state's time and
  /// step, unless the series it continues already ends there).
  RunOutput(const Scene& scene, const RunOptions& opt);
  /// A frame of the model's current state.
  void frame(double time, long step) { frames_.write(time, step); }
  /// A row of the probes table.
  void probeRow(double time, const std::map<std::string, double>& values);
  /// Stores a further table (energy history, residual history).
  void table(const std::string& name, const std::vector<std::string>& columns,
             const std::vector<std::vector<double>>& data);
  /// Writes the probes table, if a row was recorded, and closes the file.
  void close();
  /// Over the rows recorded (the output times and the end): each probe's largest and smallest value and
  /// the first time it took them, {NAME: {max, time_of_max, min, time_of_min}} (null without rows): a peak
  /// force, the time to full inflation. As fine as the output interval.
  nlohmann::json extremes() const;

 private:
  SceneFrames frames_;
  std::vector<std::string> probeNames_;
  std::vector<std::vector<double>> probeRows_;  ///< time, then one column per probe
};

/// The file a run stopped for `reason` keeps its state in (empty path: none).
std::filesystem::path stopStateFile(const RunOptions& opt, StopReason reason);

/// Keeps the state of a stopped run (see stopStateFile), records its name in result.stateFile and ends
/// result.diagnosis (already set) with where it is. A failure to write is added to the diagnosis rather
/// than thrown: the run's own report must still come out.
void saveStopState(const RunOptions& opt, const StateSnapshot& state, RunResult& result);

/// The end of every run: summary.json (scene, title, stop reason, effects, probes, `stats`, diagnosis, state
/// file) stored in the result and in DIR, then on the terminal `stopLine` (unless quiet), the probe values
/// (unless quiet) and the diagnosis of a run that did not end normally (stderr).
void finishRun(const Scene& scene, RunResult& result, const RunOptions& opt, nlohmann::json stats,
               const std::string& stopLine);

}  // namespace fsi::structure
