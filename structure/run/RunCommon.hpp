#pragma once
// What the explicit run and the dynamic-relaxation run share around their loops: the head of summary.json,
// writing it, and the stop handling — the state a stopped run keeps on disk (last_good_state.h5 after an
// instability, interrupted_state.h5 after Ctrl-C) and the report on the terminal.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "structure/io/StateFile.hpp"
#include "structure/run/Simulation.hpp"

namespace fsi::structure {

/// The parts of summary.json every solver writes.
nlohmann::json summaryHead(const Scene& scene, const RunResult& result);

/// Stores the summary (with the diagnosis, if any) in the result and in DIR/summary.json.
void writeSummary(nlohmann::json s, RunResult& result, const RunOptions& opt);

/// The file a run stopped for `reason` keeps its state in (empty path: none).
std::filesystem::path stopStateFile(const RunOptions& opt, StopReason reason);

/// Writes the state of a stopped run (see stopStateFile) and records its name in result.stateFile. A failure
/// to write is added to the diagnosis rather than thrown: the run's own report must still come out.
void writeStopState(const RunOptions& opt, const StateSnapshot& state, RunResult& result);

/// Probe values (unless quiet) and the diagnosis of a run that did not end normally, on stderr.
void printProbesAndDiagnosis(const RunResult& result, bool quiet);

}  // namespace fsi::structure
