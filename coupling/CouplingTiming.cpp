#include "coupling/CouplingTiming.hpp"

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <system_error>

#include "structure/model/Error.hpp"

namespace fsi::coupling {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json toJson(const TimingSegment& s) {
  return json{{"start_time", s.startTime},
              {"end_time", s.endTime},
              {"wall_seconds", s.wallSeconds},
              {"transfer_seconds", s.transferSeconds},
              {"structure_seconds", s.structureSeconds},
              {"checkpoint_seconds", s.checkpointSeconds},
              {"windows", s.windows},
              {"fluid_solves", s.fluidSolves},
              {"iterations", s.iterations},
              {"mean_iterations", s.windows > 0 ? double(s.iterations) / double(s.windows) : 0.0},
              {"max_iterations", s.maxIterations},
              {"not_converged", s.notConverged},
              {"structural_steps", s.structuralSteps},
              {"ranks", s.ranks}};
}

TimingSegment fromJson(const json& j) {
  TimingSegment s;
  s.startTime = j.at("start_time").get<double>();
  s.endTime = j.at("end_time").get<double>();
  s.wallSeconds = j.at("wall_seconds").get<double>();
  s.transferSeconds = j.at("transfer_seconds").get<double>();
  s.structureSeconds = j.at("structure_seconds").get<double>();
  s.checkpointSeconds = j.at("checkpoint_seconds").get<double>();
  s.windows = j.at("windows").get<long>();
  s.fluidSolves = j.at("fluid_solves").get<long>();
  s.iterations = j.at("iterations").get<long>();
  s.maxIterations = j.at("max_iterations").get<long>();
  s.notConverged = j.at("not_converged").get<long>();
  s.structuralSteps = j.at("structural_steps").get<long>();
  s.ranks = j.at("ranks").get<int>();
  return s;
}

}  // namespace

CouplingTiming::CouplingTiming(fs::path file, std::optional<double> restartTime, double tolerance)
    : file_(std::move(file)) {
  std::error_code ec;
  if (!restartTime || !fs::exists(file_, ec)) return;
  try {
    std::ifstream is(file_);
    const json j = json::parse(is);
    // A file from before segments were recorded has no per-segment data to continue: it is replaced.
    if (!j.contains("segments")) return;
    for (const json& s : j.at("segments")) {
      const TimingSegment seg = fromJson(s);
      if (seg.startTime < *restartTime - tolerance) earlier_.push_back(seg);
    }
  } catch (const json::exception& e) {
    throw InputError(file_.string() + ": cannot read the timing of the earlier run segments: " + e.what() +
                     " (move the file away to start it again)");
  }
}

TimingSegment CouplingTiming::total(const TimingSegment& current) const {
  TimingSegment t = earlier_.empty() ? current : earlier_.front();
  if (earlier_.empty()) return t;
  t.maxIterations = 0;
  t.wallSeconds = t.transferSeconds = t.structureSeconds = t.checkpointSeconds = 0;
  t.windows = t.fluidSolves = t.iterations = t.notConverged = t.structuralSteps = 0;
  std::vector<TimingSegment> all = earlier_;
  all.push_back(current);
  for (const TimingSegment& s : all) {
    t.wallSeconds += s.wallSeconds;
    t.transferSeconds += s.transferSeconds;
    t.structureSeconds += s.structureSeconds;
    t.checkpointSeconds += s.checkpointSeconds;
    t.windows += s.windows;
    t.fluidSolves += s.fluidSolves;
    t.iterations += s.iterations;
    t.maxIterations = std::max(t.maxIterations, s.maxIterations);
    t.notConverged += s.notConverged;
    t.structuralSteps += s.structuralSteps;
  }
  t.endTime = current.endTime;
  t.ranks = current.ranks;
  return t;
}

void CouplingTiming::write(const TimingSegment& current) const {
  json out = toJson(total(current));
  json segments = json::array(), restarts = json::array();
  for (const TimingSegment& s : earlier_) segments.push_back(toJson(s));
  segments.push_back(toJson(current));
  for (std::size_t i = 1; i < segments.size(); ++i) restarts.push_back(segments[i]["start_time"]);
  out["restart_times"] = restarts;
  out["segments"] = segments;
  fs::path tmp = file_;
  tmp += ".tmp";
  {
    std::ofstream os(tmp, std::ios::trunc);
    os << out.dump(2) << '\n';
    os.close();
    if (!os) throw std::runtime_error("cannot write " + tmp.string());
  }
  fs::rename(tmp, file_);
}

}  // namespace fsi::coupling
