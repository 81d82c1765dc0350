#include "structure/run/RunCommon.hpp"

#include <fmt/format.h>

#include <exception>
#include <fstream>

namespace fsi::structure {

nlohmann::json summaryHead(const Scene& scene, const RunResult& result) {
  nlohmann::json s;
  s["scene"] = scene.file.string();
  s["title"] = scene.title;
  s["stop_reason"] = toString(result.reason);
  s["effects"] = scene.enabledEffects;
  s["probes"] = nlohmann::json::object();
  for (const auto& [k, v] : result.probes) s["probes"][k] = v;
  return s;
}

void writeSummary(nlohmann::json s, RunResult& result, const RunOptions& opt) {
  if (!result.diagnosis.empty()) s["diagnosis"] = result.diagnosis;
  if (!result.stateFile.empty()) s["state_file"] = result.stateFile.filename().string();
  result.summary = s;
  std::ofstream(opt.outDir / "summary.json") << s.dump(2) << "\n";
}

std::filesystem::path stopStateFile(const RunOptions& opt, StopReason reason) {
  switch (reason) {
    case StopReason::Unstable:
      return opt.outDir / "last_good_state.h5";
    case StopReason::Interrupted:
      return opt.outDir / "interrupted_state.h5";
    default:
      return {};
  }
}

void writeStopState(const RunOptions& opt, const StateSnapshot& state, RunResult& result) {
  const std::filesystem::path file = stopStateFile(opt, result.reason);
  if (file.empty()) return;
  try {
    writeState(file, state);
    result.stateFile = file;
  } catch (const std::exception& e) {
    result.diagnosis += fmt::format(" The state could not be saved: {}", e.what());
  }
}

void printProbesAndDiagnosis(const RunResult& result, bool quiet) {
  if (!quiet)
    for (const auto& [k, v] : result.probes) fmt::print("probe  {} = {:.8g}\n", k, v);
  if (result.diagnosis.empty()) return;
  fmt::print(stderr, "{}: {}\n", result.reason == StopReason::Interrupted ? "interrupted" : "error",
             result.diagnosis);
  std::fflush(stderr);
}

}  // namespace fsi::structure
