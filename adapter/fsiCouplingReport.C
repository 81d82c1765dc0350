#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

#include "OSspecific.H"
#include "Time.H"
#include "coupling/CouplingCsv.hpp"
#include "coupling/CouplingTiming.hpp"
#include "coupling/scheme/CouplingScheme.hpp"
#include "fsiCouplingReport.H"
#include "fsiInterfaceTransfer.H"
#include "fsiMeshGuard.H"
#include "structure/run/Simulation.hpp"

namespace Foam {

namespace {

// h:mm:ss, for wall time and ETA on the progress line.
std::string hms(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char buf[32];
  std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  return buf;
}

}  // namespace

scalar fsiNamedTime(const Time& time, scalar t) {
  return std::stod(std::string(time.timeName(t)));
}

fsiCouplingReport::fsiCouplingReport(const Time& time, const fsiCouplingConfig& config,
                                     Clock::time_point wallStart)
    : time_(time), config_(config), wallStart_(wallStart) {
  const scalar dt = time_.deltaTValue();
  endTime_ = time_.endTime().value();
  segmentStart_ = time_.value();
  fresh_ = time_.value() <= 0.5 * dt;
  // Progress: every window of a short run, about 40 lines for a long one; windows counted from t = 0.
  windowsTotal_ = max(label(1), label(std::lround(endTime_ / dt)));
  progressEvery_ = config.progress ? *config.progress : max(label(1), (windowsTotal_ + 39) / 40);
}

fsiCouplingReport::~fsiCouplingReport() = default;

std::string fsiCouplingReport::csvHeader(fsi::coupling::StructureParticipant& structure) const {
  std::string header =
      "time,iterations,converged,residual,Fx_fluid,Fy_fluid,Fz_fluid,Fx_structure,Fy_structure,Fz_"
      "structure,Mx_fluid,My_fluid,Mz_fluid,Mx_structure,My_structure,Mz_structure";
  for (const auto& [name, value] : fsi::structure::evaluateProbes(structure.scene())) header += ',' + name;
  // Equilibrium mode: what each window's relaxation did, and how near equilibrium it ended.
  if (config_.equilibrium()) header += ",subcycles,kinetic_resets,equilibrium_residual";
  return header;
}

void fsiCouplingReport::open(fsi::coupling::StructureParticipant& structure) {
  const scalar dt = time_.deltaTValue();
  const scalar t0 = fsiNamedTime(time_, time_.value());
  const fileName outDir = time_.globalPath() / "structure";
  // Output: one series per run. A restart continues results.h5, coupling.csv and timing.json after
  // dropping what lies later than the restart time (a restart from an earlier time leaves no stale
  // future); everything within half a window of t0 belongs to t0.
  mkDir(outDir);
  const std::optional<double> keepUntil = fresh_ ? std::nullopt : std::optional<double>(t0 + 0.5 * dt);
  structure.openResults(std::string(outDir / "results.h5"), keepUntil);
  if (fresh_) {
    structure.recordHistory(t0);  // the state at t = 0 opens the energy and probe tables
  } else {
    structure.noteRestart(t0);
  }
  structure.writeResults(t0);  // t = 0, or the restart time if the earlier run has no frame there
  csv_ = std::make_unique<fsi::coupling::CouplingCsv>(
      std::string(outDir / "coupling.csv"), csvHeader(structure),
      fresh_ ? std::nullopt
             : std::optional<fsi::coupling::CsvRestart>(
                   fsi::coupling::CsvRestart{*keepUntil, time_.timeName()}));
  timing_ = std::make_unique<fsi::coupling::CouplingTiming>(
      std::string(outDir / "timing.json"), fresh_ ? std::nullopt : std::optional<double>(t0), 0.5 * dt);
  stepsAtStart_ = structure.structuralSteps();
}

void fsiCouplingReport::startup(const fsi::coupling::StructureParticipant& structure) const {
  const fsi::coupling::OptionValues& o = config_.options;
  const scalar dt = time_.deltaTValue();
  Info << "[fsi] structure " << config_.sceneGiven.c_str() << ": " << structure.numInterfaceNodes()
       << " interface nodes, ";
  if (config_.equilibrium()) {
    Info << "equilibrium mode: " << o.integer("equilibriumSteps")
         << " damped pseudo-steps per window (kinetic damping";
    if (o.text("equilibriumStart") == "carry") {
      Info << ", the motion carried across windows";
      if (o.real("equilibriumCarryFrom") > 0)
        Info << " from t = " << o.real("equilibriumCarryFrom") << " s, from rest before";
    }
    Info << ")";
  } else {
    Info << structure.subcyclesFor(dt) << " structural steps per window of " << dt << " s";
  }
  if (o.real("loadRelaxation") < 1) Info << ", load relaxation " << o.real("loadRelaxation");
  Info << endl;
  if (config_.implicit) {
    const std::string& acc = o.text("acceleration");
    Info << "[fsi] implicit coupling, " << acc.c_str() << " (omega " << o.real("omega");
    if (o.has("reuse")) Info << ", reuse " << o.integer("reuse");
    Info << "), tolerance " << o.real("tolerance") << ", at most " << o.integer("maxIterations")
         << " iterations, extrapolation " << o.integer("extrapolation") << endl;
  } else {
    Info << "[fsi] staggered coupling, extrapolation " << o.integer("extrapolation") << endl;
  }
  if (!fresh_)
    Info << "[fsi] restart at t = " << time_.timeName() << ": structure/results.h5 ("
         << structure.framesWritten() << " frames up to here), coupling.csv and timing.json continue" << endl;
  Info << "[fsi] t = " << time_.timeName() << " to " << endTime_ << " s, " << windowsTotal_ << " windows; ";
  if (progressEvery_ > 0)
    Info << "progress every " << progressEvery_ << " window(s)" << endl;
  else
    Info << "no progress lines" << endl;
}

void fsiCouplingReport::window(const vector& fluidTotal, const std::vector<double>& loads, bool finished,
                               fsi::coupling::StructureParticipant& structure,
                               const fsi::coupling::CouplingScheme& scheme,
                               const fsiInterfaceTransfer& transfer) {
  // The fluid's load as transferred to the structure nodes (the transfer's conservation check; with
  // loadRelaxation < 1 the structure gets the relaxed mix of it and the previous window's load).
  vector structureTotal = Zero;
  for (std::size_t k = 0; k < loads.size(); ++k) structureTotal[k % 3] += loads[k];
  const auto& w = scheme.lastWindow();
  Info << "fsiCoupling: t = " << time_.value() << " s, window " << w.window << ": " << w.iterations
       << " iteration(s)" << (w.converged || !config_.implicit ? "" : " NOT CONVERGED")
       << ", interface force fluid " << fluidTotal << " N, structure " << structureTotal << " N";
  if (const fsi::coupling::MomentCorrection* c = transfer.momentCorrection()) {
    const double defect =
        std::sqrt(c->defect[0] * c->defect[0] + c->defect[1] * c->defect[1] + c->defect[2] * c->defect[2]);
    Info << ", moment made up " << defect / max(mag(transfer.fluidMoment()), VSMALL)
         << " of the fluid's (largest nodal " << c->largestNodalForce << " N)";
  }
  Info << endl;
  // The row's time is the fluid's time name: the rows line up with the time directories exactly.
  const std::map<std::string, double> probes = structure.recordHistory(fsiNamedTime(time_, time_.value()));
  char buf[64];
  std::string row = std::string(time_.timeName()) + ',' + std::to_string(w.iterations) + ',' +
                    std::to_string(int(w.converged));
  auto add = [&](double v) {
    std::snprintf(buf, sizeof buf, ",%.12g", v);
    row += buf;
  };
  add(w.relativeResidual);
  for (direction k = 0; k < 3; ++k) add(fluidTotal[k]);
  for (direction k = 0; k < 3; ++k) add(structureTotal[k]);
  for (direction k = 0; k < 3; ++k) add(transfer.fluidMoment()[k]);
  for (direction k = 0; k < 3; ++k) add(transfer.structureMoment()[k]);
  for (const auto& [name, value] : probes) add(value);
  if (config_.equilibrium()) {
    const fsi::coupling::EquilibriumReport r = structure.equilibriumReport();
    row += ',' + std::to_string(r.steps) + ',' + std::to_string(r.resets);
    add(structure.staticResidualRatio());
  }
  csv_->row(row);
  progress(fluidTotal, finished, scheme);
}

void fsiCouplingReport::progress(const vector& fluidTotal, bool finished,
                                 const fsi::coupling::CouplingScheme& scheme) {
  if (progressEvery_ <= 0) return;
  const scalar dt = time_.deltaTValue();
  const long n = std::lround(time_.value() / dt), total = std::lround(endTime_ / dt);
  const double wall = seconds(wallStart_, Clock::now());
  const long done = std::lround((time_.value() - segmentStart_) / dt);
  // Every progressEvery windows and the last; also the segment's first window (an ETA at once) and any window
  // kProgressSeconds of wall time after the last line (slow windows still show that the run is alive)
  if (n % progressEvery_ != 0 && !finished && done != 1 && wall - lastProgressWall_ < kProgressSeconds)
    return;
  lastProgressWall_ = wall;
  const auto& w = scheme.lastWindow();
  const auto& s = scheme.statistics();
  const double eta = done > 0 ? wall * double(total - n) / double(done) : 0.0;
  char residual[32] = "-";
  if (config_.implicit) std::snprintf(residual, sizeof residual, "%.2e", w.relativeResidual);
  char line[256];
  // Short enough for one terminal line (< 160 characters even at a million windows and 100 hours).
  std::snprintf(
      line, sizeof line,
      "[fsi] t %s/%g s (%.1f%%)  window %ld/%ld  iter %d (mean %.1f)  res %s  F (%.3g %.3g %.3g) N  "
      "wall %s  ETA %s",
      time_.timeName().c_str(), endTime_, 100.0 * time_.value() / endTime_, n, total, w.iterations,
      s.meanIterations(), residual, fluidTotal.x(), fluidTotal.y(), fluidTotal.z(), hms(wall).c_str(),
      hms(eta).c_str());
  Info << line << endl;
}

fsi::coupling::TimingSegment fsiCouplingReport::segment(double wall,
                                                        const fsi::coupling::StructureParticipant& structure,
                                                        const fsi::coupling::CouplingScheme& scheme) const {
  fsi::coupling::TimingSegment seg;
  const auto& s = scheme.statistics();
  seg.startTime = fsiNamedTime(time_, segmentStart_);
  seg.endTime = fsiNamedTime(time_, scheme.time());
  seg.wallSeconds = wall;
  seg.transferSeconds = tTransfer;
  seg.structureSeconds = tStructure;
  seg.checkpointSeconds = tCheckpoint;
  seg.windows = s.windows;
  seg.fluidSolves = fluidSolves;
  seg.iterations = s.iterations;
  seg.maxIterations = s.maxIterations;
  seg.notConverged = s.notConverged;
  seg.structuralSteps = structure.structuralSteps() - stepsAtStart_;
  seg.ranks = Pstream::nProcs();
  return seg;
}

void fsiCouplingReport::writeTiming(const fsi::coupling::StructureParticipant& structure,
                                    const fsi::coupling::CouplingScheme& scheme) const {
  timing_->write(segment(seconds(wallStart_, Clock::now()), structure, scheme));
}

void fsiCouplingReport::summary(const fsi::coupling::StructureParticipant& structure,
                                const fsi::coupling::CouplingScheme& scheme,
                                const fsiInterfaceTransfer& transfer, const fsiMeshGuard* meshGuard) const {
  const double wall = seconds(wallStart_, Clock::now());
  const double ours = tTransfer + tStructure + tCheckpoint;
  const auto& s = scheme.statistics();
  Info << "[fsi] " << s.windows << " windows, " << fluidSolves << " fluid solves (" << s.meanIterations()
       << " per window, at most " << s.maxIterations << ", " << s.notConverged << " not converged); "
       << structure.structuralSteps() - stepsAtStart_ << " structural steps" << nl << "[fsi] wall time "
       << wall << " s: transfer " << tTransfer << " s, structure " << tStructure << " s, checkpoints "
       << tCheckpoint << " s = " << 100.0 * ours / max(wall, 1e-300) << " % of the run" << endl;
  // Two lines: [fsi] lines stay under 160 characters (tests/adapter `progress`).
  const fsiInterfaceTransfer::Timers& t = transfer.timers();
  Info << "[fsi] set-up " << tSetup << " s (structure, projection, first displacement)" << nl
       << "[fsi] transfer parts (master rank): gather " << t.gather << " s, load projection "
       << t.loadProjection << " s, displacement projection " << t.displacementProjection << " s, scatter "
       << t.scatter << " s" << endl;
  if (meshGuard)
    Info << "[fsi] mesh guard: smallest cell volume ratio " << meshGuard->worstRatio()
         << " (at t = " << meshGuard->worstRatioTime() << " s; stop below " << meshGuard->minVolumeRatio()
         << "), largest non-orthogonality " << meshGuard->maxNonOrthSeen() << " deg, checks "
         << meshGuard->seconds() << " s" << endl;
  const fsi::coupling::TimingSegment seg = segment(wall, structure, scheme);
  if (!timing_->earlier().empty()) {
    const fsi::coupling::TimingSegment all = timing_->total(seg);
    Info << "[fsi] all " << timing_->earlier().size() + 1 << " run segments: " << all.windows << " windows, "
         << all.fluidSolves << " fluid solves, wall time " << all.wallSeconds << " s" << endl;
  }
  try {
    timing_->write(seg);
  } catch (const std::exception& e) {
    WarningInFunction << "fsiCoupling: " << e.what() << endl;
  }
}

}  // namespace Foam
