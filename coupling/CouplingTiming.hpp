#pragma once
// CouplingTiming: structure/timing.json of a coupled run — where the wall time went and what the coupling
// cost, per run segment (a fresh start or a restart) and added up over the segments:
//
//   { <totals: the keys of a segment, summed; max_iterations the largest; mean_iterations = iterations /
//      windows; start_time of the first, end_time and ranks of the last segment>,
//     "restart_times": [the start times of the segments after the first],
//     "segments": [ {"start_time", "end_time", "wall_seconds", "transfer_seconds", "structure_seconds",
//                    "checkpoint_seconds", "windows", "fluid_solves", "iterations", "mean_iterations",
//                    "max_iterations", "not_converged", "structural_steps", "ranks"}, ... ] }
//
// A restart keeps the segments that started before the restart time (those starting later belong to a
// discarded future; a segment that ran past the restart time is kept whole: its wall time was spent).

#include <filesystem>
#include <optional>
#include <vector>

namespace fsi::coupling {

struct TimingSegment {
  double startTime = 0, endTime = 0;
  double wallSeconds = 0, transferSeconds = 0, structureSeconds = 0, checkpointSeconds = 0;
  long windows = 0, fluidSolves = 0, iterations = 0, maxIterations = 0, notConverged = 0, structuralSteps = 0;
  int ranks = 1;
};

class CouplingTiming {
 public:
  /// Fresh run: no earlier segments. Restart at `restartTime`: the segments of `file` (if it exists) that
  /// started before restartTime - tolerance. Throws fsi::InputError naming the file if it cannot be read.
  CouplingTiming(std::filesystem::path file, std::optional<double> restartTime = std::nullopt,
                 double tolerance = 0);
  /// Rewrites the file: the earlier segments, then `current`, and the totals.
  void write(const TimingSegment& current) const;
  const std::vector<TimingSegment>& earlier() const { return earlier_; }
  /// Sum over the earlier segments and `current` (what write() puts at the top level).
  TimingSegment total(const TimingSegment& current) const;

 private:
  std::filesystem::path file_;
  std::vector<TimingSegment> earlier_;
};

}  // namespace fsi::coupling
