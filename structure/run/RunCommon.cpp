#include "structure/run/RunCommon.hpp"

#include <fmt/format.h>

#include <csignal>
#include <cstdio>
#include <exception>
#include <fstream>

#include "structure/elements/ElementKind.hpp"
#include "structure/io/StateFile.hpp"

namespace fsi::structure {

std::string modelCounts(const Model& model) {
  std::string line = fmt::format("{} nodes", model.nodes.count);
  for (const ElementKind* kind : elementKinds()) {
    const int n = kind->count(model);
    if (n > 0) line += fmt::format(", {} {}", n, kind->label());
  }
  return line;
}

void addElementKindStats(const Model& model, const double* x, nlohmann::json& stats) {
  nlohmann::json kinds = nlohmann::json::object();
  for (const ElementKind* kind : elementKinds()) {
    const int n = kind->count(model);
    stats[kind->name() + "_elements"] = n;
    if (n == 0) continue;
    nlohmann::json k;
    k["count"] = n;
    for (const auto& [name, value] : kind->report(model, x)) k[name] = value;
    kinds[kind->name()] = std::move(k);
  }
  stats["element_kinds"] = std::move(kinds);
}

std::string signalName(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    default:
      return fmt::format("signal {}", signal);
  }
}

void printSceneLine(const Scene& scene) {
  fmt::print("scene  {}{}\n", scene.file.string(), scene.title.empty() ? "" : "  (" + scene.title + ")");
}

RunClock::RunClock(double progressSeconds)
    : progressSeconds_(progressSeconds), start_(Clock::now()), lastPrint_(start_) {}

double RunClock::seconds() const {
  return std::chrono::duration<double>(Clock::now() - start_).count();
}

bool RunClock::progressDue(bool soon) {
  const auto now = Clock::now();
  const double since = std::chrono::duration<double>(now - lastPrint_).count();
  if (!(since >= progressSeconds_ || (soon && since >= 0.02 * progressSeconds_))) return false;
  lastPrint_ = now;
  return true;
}

RunOutput::RunOutput(const Scene& scene, const RunOptions& opt)
    : frames_(
          *scene.model, scene.constraints, scene.output.fields, opt.outDir / "results.h5",
          opt.startState && opt.continueSeries ? std::optional<double>(opt.startState->time) : std::nullopt) {
  const double time = opt.startState ? opt.startState->time : 0.0;
  const long step = opt.startState ? opt.startState->step : 0;
  if (!(frames_.lastTime() >= time)) frames_.write(time, step);
  for (const auto& p : scene.probes) probeNames_.push_back(p.name);
  probeRows_.resize(probeNames_.size() + 1);
}

void RunOutput::probeRow(double time, const std::map<std::string, double>& values) {
  probeRows_[0].push_back(time);
  for (std::size_t i = 0; i < probeNames_.size(); ++i) probeRows_[i + 1].push_back(values.at(probeNames_[i]));
}

void RunOutput::table(const std::string& name, const std::vector<std::string>& columns,
                      const std::vector<std::vector<double>>& data) {
  frames_.writer().writeTable(name, columns, data);
}

nlohmann::json RunOutput::extremes() const {
  if (probeRows_[0].empty()) return nullptr;
  nlohmann::json out = nlohmann::json::object();
  const std::vector<double>& t = probeRows_[0];
  for (std::size_t i = 0; i < probeNames_.size(); ++i) {
    const std::vector<double>& v = probeRows_[i + 1];
    std::size_t hi = 0, lo = 0;
    for (std::size_t r = 1; r < v.size(); ++r) {
      if (v[r] > v[hi]) hi = r;
      if (v[r] < v[lo]) lo = r;
    }
    out[probeNames_[i]] = {{"max", v[hi]}, {"time_of_max", t[hi]}, {"min", v[lo]}, {"time_of_min", t[lo]}};
  }
  return out;
}

void RunOutput::close() {
  if (!probeRows_[0].empty()) {
    std::vector<std::string> cols{"time"};
    cols.insert(cols.end(), probeNames_.begin(), probeNames_.end());
    frames_.writer().writeTable("probes", cols, probeRows_);
  }
  frames_.writer().close();
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

void saveStopState(const RunOptions& opt, const StateSnapshot& state, RunResult& result) {
  const std::filesystem::path file = stopStateFile(opt, result.reason);
  if (file.empty()) return;
  // An instability's diagnosis is sentences, an interrupt's one line.
  const bool sentences = result.reason != StopReason::Interrupted;
  try {
    writeState(file, state);
    result.stateFile = file;
    result.diagnosis += sentences ? " Saved in " + file.string() + "." : "; state saved in " + file.string();
  } catch (const std::exception& e) {
    result.diagnosis += fmt::format(
        sentences ? " The state could not be saved: {}" : "; the state could not be saved: {}", e.what());
  }
}

void finishRun(const Scene& scene, RunResult& result, const RunOptions& opt, nlohmann::json stats,
               const std::string& stopLine) {
  if (result.reason == StopReason::Interrupted && opt.stop != nullptr) result.stopSignal = opt.stop->signal();
  nlohmann::json s;
  s["scene"] = scene.file.string();
  s["title"] = scene.title;
  s["stop_reason"] = toString(result.reason);
  s["effects"] = scene.enabledEffects;
  s["probes"] = nlohmann::json::object();
  for (const auto& [k, v] : result.probes) s["probes"][k] = v;
  if (!result.probeExtremes.is_null()) s["probe_extremes"] = result.probeExtremes;
  s["stats"] = std::move(stats);
  if (!opt.startFrom.is_null()) s["start_from"] = opt.startFrom;
  if (!result.diagnosis.empty()) s["diagnosis"] = result.diagnosis;
  if (!result.stateFile.empty()) s["state_file"] = result.stateFile.filename().string();
  if (result.stopSignal != 0) s["stop_signal"] = signalName(result.stopSignal);
  result.summary = s;
  std::ofstream(opt.outDir / "summary.json") << s.dump(2) << "\n";

  if (!opt.quiet) {
    fmt::print("{}\n", stopLine);
    for (const auto& [k, v] : result.probes) fmt::print("probe  {} = {:.8g}\n", k, v);
  }
  if (result.diagnosis.empty()) return;
  if (result.reason == StopReason::Interrupted)
    fmt::print(stderr, "interrupted{}: {}\n",
               result.stopSignal != 0 ? " (" + signalName(result.stopSignal) + ")" : std::string(),
               result.diagnosis);
  else
    fmt::print(stderr, "error: {}\n", result.diagnosis);
  std::fflush(stderr);
}

}  // namespace fsi::structure
