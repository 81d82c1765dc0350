#include "structure/run/Simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <fstream>
#include <limits>

#include "structure/io/ResultsWriter.hpp"
#include "structure/io/SceneFrames.hpp"
#include "structure/io/StateFile.hpp"
#include "structure/run/InstabilityDiagnosis.hpp"

namespace fsi::structure {

namespace {
volatile std::sig_atomic_t gInterrupted = 0;
extern "C" void onInterrupt(int) {
  gInterrupted = 1;
}

double componentOf(const double* u, int component) {
  if (component < 3) return u[component];
  return std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
}

double reduceValues(const std::vector<double>& vals, ProbeSpec::Reduce r) {
  switch (r) {
    case ProbeSpec::Reduce::Value:
      return vals.front();
    case ProbeSpec::Reduce::Mean: {
      double s = 0;
      for (double v : vals) s += v;
      return s / double(vals.size());
    }
    case ProbeSpec::Reduce::Max:
      return *std::max_element(vals.begin(), vals.end());
    case ProbeSpec::Reduce::Min:
      return *std::min_element(vals.begin(), vals.end());
    case ProbeSpec::Reduce::Sum: {
      double s = 0;
      for (double v : vals) s += v;
      return s;
    }
  }
  return 0.0;
}
}  // namespace

void installInterruptHandler() {
  std::signal(SIGINT, onInterrupt);
}

std::string toString(StopReason r) {
  switch (r) {
    case StopReason::EndTime:
      return "end_time";
    case StopReason::Static:
      return "static";
    case StopReason::NotConverged:
      return "not_converged";
    case StopReason::Unstable:
      return "unstable";
    case StopReason::Interrupted:
      return "interrupted";
  }
  return "?";
}

int RunResult::exitCode() const {
  switch (reason) {
    case StopReason::Unstable:
      return 3;
    case StopReason::Interrupted:
      return 130;
    case StopReason::NotConverged:
      return 4;
    default:
      return 0;
  }
}

std::map<std::string, double> evaluateProbes(const Scene& scene) {
  const Model& model = *scene.model;
  const Nodes& N = model.nodes;
  std::map<std::string, double> out;
  MembraneStressField stress;
  bool haveStress = false;
  for (const ProbeSpec& p : scene.probes) {
    std::vector<double> vals;
    switch (p.type) {
      case ProbeSpec::Type::Position:
        for (int n : p.nodes) {
          double r[3];
          for (int k = 0; k < 3; ++k) r[k] = N.x[3 * n + k] - (p.component == 4 ? p.center[k] : 0.0);
          vals.push_back(componentOf(r, p.component == 4 ? 3 : p.component));
        }
        break;
      case ProbeSpec::Type::Displacement:
        for (int n : p.nodes) {
          const double u[3] = {N.x[3 * n] - N.X[3 * n], N.x[3 * n + 1] - N.X[3 * n + 1],
                               N.x[3 * n + 2] - N.X[3 * n + 2]};
          if (p.component == 4) {
            double r = 0, r0 = 0;
            for (int k = 0; k < 3; ++k) {
              r += std::pow(N.x[3 * n + k] - p.center[k], 2);
              r0 += std::pow(N.X[3 * n + k] - p.center[k], 2);
            }
            vals.push_back(std::sqrt(r) - std::sqrt(r0));
          } else {
            vals.push_back(componentOf(u, p.component));
          }
        }
        break;
      case ProbeSpec::Type::Reaction: {
        double r[3] = {0, 0, 0};
        for (int n : p.nodes)
          for (int k = 0; k < 3; ++k) r[k] += N.fint[3 * n + k] - N.fext[3 * n + k];
        vals.push_back(componentOf(r, p.component));
        break;
      }
      case ProbeSpec::Type::Volume: {
        // Divergence theorem about `center`: symmetry planes through the centre add nothing.
        double v = 0;
        for (int e : p.triangles) {
          const int* c = &model.membranes.conn[3 * e];
          double a[3], b[3], d[3];
          for (int k = 0; k < 3; ++k) {
            a[k] = N.x[3 * c[0] + k] - p.center[k];
            b[k] = N.x[3 * c[1] + k] - p.center[k];
            d[k] = N.x[3 * c[2] + k] - p.center[k];
          }
          v += a[0] * (b[1] * d[2] - b[2] * d[1]) + a[1] * (b[2] * d[0] - b[0] * d[2]) +
               a[2] * (b[0] * d[1] - b[1] * d[0]);
        }
        vals.push_back(v / 6.0);
        break;
      }
      case ProbeSpec::Type::Stress:
        if (!haveStress && scene.membrane) scene.membrane->evaluate(N.x.data(), stress), haveStress = true;
        for (int e : p.triangles)
          vals.push_back(stress.principal[2 * e + (p.quantity == "min_principal" ? 1 : 0)]);
        break;
    }
    out[p.name] = reduceValues(vals, p.reduce);
  }
  return out;
}

namespace {

struct Snapshot {
  std::vector<double> x, v;
  double time = 0, dt = 0;
  long steps = 0;
};

}  // namespace

namespace {

// The parts of summary.json every solver writes.
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

// Stores the summary in the result and in DIR/summary.json; reports the diagnosis on stderr.
void writeSummary(nlohmann::json s, RunResult& result, const RunOptions& opt) {
  if (!result.diagnosis.empty()) s["diagnosis"] = result.diagnosis;
  result.summary = s;
  std::ofstream(opt.outDir / "summary.json") << s.dump(2) << "\n";
}

void printProbesAndDiagnosis(const RunResult& result, bool quiet) {
  if (!quiet)
    for (const auto& [k, v] : result.probes) fmt::print("probe  {} = {:.8g}\n", k, v);
  if (!result.diagnosis.empty()) fmt::print(stderr, "error: {}\n", result.diagnosis);
}

RunResult runRelaxation(Scene& scene, const RunOptions& opt) {
  using Clock = std::chrono::steady_clock;
  namespace fs = std::filesystem;
  fs::create_directories(opt.outDir);
  Model& model = *scene.model;
  Nodes& N = model.nodes;
  const RelaxationSettings& rs = scene.solver.relaxation;
  RunResult result;
  if (!opt.quiet) {
    fmt::print("scene  {}{}\n", scene.file.string(), scene.title.empty() ? "" : "  (" + scene.title + ")");
    fmt::print(
        "model  {} nodes, {} membrane triangles, {} cables; dynamic relaxation {} (λ = {:.3g}), ε = {:.3g}, "
        "{} increment(s)\n",
        N.count, model.membranes.count, model.cables.count, scene.solver.method,
        rs.lambda > 0 ? rs.lambda : defaultLambda(rs), rs.tolerance, rs.increments);
  }
  SceneFrames frames(scene, opt.outDir / "results.h5");
  frames.write(0.0, 0);
  DynamicRelaxation dr(model, scene.effectList(), scene.constraints, rs);
  gInterrupted = 0;
  const auto wall0 = Clock::now();
  const RelaxationResult r = dr.run(
      [&](int inc, const RelaxationResult& rr) {
        frames.write(double(inc) / rs.increments, rr.iterations);
        if (!opt.quiet)
          fmt::print("increment {}/{} converged: iteration {}, residual ratio {:.3g}, KE/U {:.3g}\n", inc,
                     rs.increments, rr.iterations, rr.residualRatio, rr.energyRatio);
      },
      [] { return gInterrupted != 0; });
  const double wall = std::chrono::duration<double>(Clock::now() - wall0).count();
  result.reason = r.converged                  ? StopReason::Static
                  : r.diverged                 ? StopReason::Unstable
                  : r.message == "interrupted" ? StopReason::Interrupted
                                               : StopReason::NotConverged;
  if (!r.converged) {
    frames.write(1.0, r.iterations);
    result.diagnosis = r.message;
  }
  result.probes = evaluateProbes(scene);
  {
    std::vector<std::vector<double>> cols(5);
    for (const auto& h : r.history) {
      cols[0].push_back(double(h.iteration));
      cols[1].push_back(h.residualRatio);
      cols[2].push_back(h.energyRatio);
      cols[3].push_back(h.kinetic);
      cols[4].push_back(h.strain);
    }
    frames.writer().writeTable("residual",
                               {"iteration", "residual_ratio", "energy_ratio", "kinetic", "strain"}, cols);
  }
  frames.writer().close();

  nlohmann::json s = summaryHead(scene, result);
  nlohmann::json st;
  st["solver"] = "dynamic_relaxation";
  st["method"] = scene.solver.method;
  st["lambda"] = r.lambda;
  st["iterations"] = r.iterations;
  st["converged"] = r.converged;
  st["final_residual"] = r.residualRatio;
  st["energy_ratio"] = r.energyRatio;
  st["tolerance"] = rs.tolerance;
  st["increments"] = rs.increments;
  st["kinetic_resets"] = r.kineticResets;
  st["mass_increases"] = r.massIncreases;
  st["restarts"] = r.restarts;
  st["final_lambda"] = r.finalLambda;
  st["wall_seconds"] = wall;
  st["seconds_per_iteration"] = r.iterations > 0 ? wall / double(r.iterations) : 0.0;
  st["nodes"] = N.count;
  st["dof"] = 3 * N.count;
  st["membrane_elements"] = model.membranes.count;
  st["cable_elements"] = model.cables.count;
  st["strain_energy"] = r.history.empty() ? 0.0 : r.history.back().strain;
  st["element_updates_per_second"] =
      wall > 0 ? double(model.membranes.count + model.cables.count) * double(r.iterations) / wall : 0.0;
  s["stats"] = st;
  writeSummary(s, result, opt);
  if (!opt.quiet) {
    fmt::print(
        "stop   {} after {} iterations ({} kinetic resets, {} node mass increases, {} restarts), {:.3g} s "
        "wall, {:.3g} ms per iteration, residual ratio {:.3g}, KE/U {:.3g}\n",
        toString(result.reason), r.iterations, r.kineticResets, r.massIncreases, r.restarts, wall,
        1e3 * st["seconds_per_iteration"].get<double>(), r.residualRatio, r.energyRatio);
  }
  printProbesAndDiagnosis(result, opt.quiet);
  return result;
}

}  // namespace

RunResult runSimulation(Scene& scene, const RunOptions& opt) {
  if (scene.solver.type == SolverControl::Type::DynamicRelaxation) return runRelaxation(scene, opt);
  using Clock = std::chrono::steady_clock;
  namespace fs = std::filesystem;
  fs::create_directories(opt.outDir);
  Model& model = *scene.model;
  Nodes& N = model.nodes;
  const TimeControl& tc = scene.time;
  CentralDifference cd(model, scene.effectList(), scene.constraints, tc.integrator);
  SceneFrames frames(scene, opt.outDir / "results.h5");
  RunResult result;

  if (!opt.quiet) {
    fmt::print("scene  {}{}\n", scene.file.string(), scene.title.empty() ? "" : "  (" + scene.title + ")");
    fmt::print("model  {} nodes, {} membrane triangles, {} cables; effects: ", N.count, model.membranes.count,
               model.cables.count);
    for (std::size_t i = 0; i < scene.enabledEffects.size(); ++i)
      fmt::print("{}{}", i ? ", " : "", scene.enabledEffects[i]);
    fmt::print("\n");
    if (scene.massScaling.scaledElements > 0)
      fmt::print("mass scaling: {} elements, added mass {:.4g} kg ({:.3g}% of {:.4g} kg)\n",
                 scene.massScaling.scaledElements, scene.massScaling.addedMass,
                 100 * scene.massScaling.addedFraction(), scene.massScaling.physicalMass);
  }

  frames.write(0.0, 0);
  std::vector<std::vector<double>> energyRows(8);
  std::vector<std::string> probeNames;
  for (const auto& p : scene.probes) probeNames.push_back(p.name);
  std::vector<std::vector<double>> probeRows(probeNames.size() + 1);

  Snapshot good{N.x, N.v, 0.0, 0.0, 0};
  const double tEnd = tc.endTime;
  double nextOutput = scene.output.interval > 0 ? scene.output.interval : tEnd;
  int staticHits = 0;
  bool nonFinite = false;
  const auto wall0 = Clock::now();
  auto lastPrint = wall0;
  bool printNow = false;
  gInterrupted = 0;

  while (true) {
    const double limit = std::min(nextOutput, tEnd);
    const bool monitor = (cd.steps() + 1) % tc.monitorEvery == 0;
    if (!cd.step(limit, monitor)) {
      nonFinite = true;
      result.reason = StopReason::Unstable;
      break;
    }
    if (monitor) {
      const EnergyLedger& E = cd.energy();
      const double err = E.balanceError();
      for (auto [i, v] : {std::pair{0, cd.time()},
                          {1, E.kinetic},
                          {2, E.strain},
                          {3, E.externalWork},
                          {4, E.internalWork},
                          {5, E.massDamping},
                          {6, err},
                          {7, cd.lastDt()}})
        energyRows[i].push_back(v);
      if (err > tc.energyTolerance) {
        result.reason = StopReason::Unstable;
        break;
      }
      good = {N.x, N.v, cd.time(), cd.lastDt(), cd.steps()};
      if (tc.untilStatic) {
        const bool still = E.strain > 0 && E.kinetic < tc.staticTolerance * E.strain;
        staticHits = still ? staticHits + 1 : 0;
        if (staticHits >= 3) {  // three checks in a row: not a momentary turning point
          result.reason = StopReason::Static;
          break;
        }
      }
    }
    const bool atOutput = cd.time() >= limit * (1 - 1e-12) && limit == nextOutput;
    if (atOutput && scene.output.interval > 0 && cd.time() < tEnd * (1 - 1e-12)) {
      frames.write(cd.time(), cd.steps());
      auto probes = evaluateProbes(scene);
      probeRows[0].push_back(cd.time());
      for (std::size_t i = 0; i < probeNames.size(); ++i) probeRows[i + 1].push_back(probes[probeNames[i]]);
      nextOutput += scene.output.interval;
      printNow = true;  // a progress line per output frame too (throttled below), so short runs show progress
    }
    if (cd.time() >= tEnd * (1 - 1e-12)) {
      result.reason = tc.untilStatic ? StopReason::NotConverged : StopReason::EndTime;
      break;
    }
    if (gInterrupted) {
      result.reason = StopReason::Interrupted;
      break;
    }
    if (!opt.quiet && (printNow || (cd.steps() & 255) == 0)) {
      const auto now = Clock::now();
      const double since = std::chrono::duration<double>(now - lastPrint).count();
      if (since >= opt.progressSeconds || (printNow && since >= 0.02 * opt.progressSeconds)) {
        lastPrint = now;
        const double wall = std::chrono::duration<double>(now - wall0).count();
        const EnergyLedger& E = cd.energy();
        const double eta = wall * (tEnd - cd.time()) / std::max(cd.time(), 1e-300);
        fmt::print(
            "step {:>9}  t {:.5g}/{:.5g} s  dt {:.3g} s  KE {:.4g} J  U {:.4g} J  {}  {:.0f} s left{}\n",
            cd.steps(), cd.time(), tEnd, cd.lastDt(), E.kinetic, E.strain,
            tc.untilStatic ? fmt::format("KE/U {:.2g}", E.strain > 0 ? E.kinetic / E.strain : 0.0)
                           : std::string(),
            eta, tc.untilStatic ? " (at most)" : "");
        std::fflush(stdout);
      }
      printNow = false;
    }
  }
  const double wall = std::chrono::duration<double>(Clock::now() - wall0).count();
  const long steps = cd.steps();

  if (result.reason == StopReason::Unstable) {
    result.diagnosis = diagnoseInstability(scene, cd, good.steps, good.time, nonFinite);
    // Keep the last good state: on disk as a restartable state and as the last frame of the results.
    StateSnapshot snap;
    snap.time = good.time;
    snap.step = good.steps;
    snap.dt = good.dt;
    snap.x = good.x;
    snap.v = good.v;
    writeState(opt.outDir / "last_good_state.h5", snap);
    cd.restore(good.x, good.v, good.time, good.dt, good.steps);
    frames.write(good.time, good.steps);
  } else {
    if (result.reason == StopReason::Interrupted) {
      StateSnapshot snap;
      snap.time = cd.time();
      snap.step = steps;
      snap.dt = cd.lastDt();
      snap.x = N.x;
      snap.v = N.v;
      writeState(opt.outDir / "interrupted_state.h5", snap);
    }
    frames.write(cd.time(), steps);
  }
  cd.evaluateForces(true);  // current forces for reactions, current strain energy for the summary
  result.probes = evaluateProbes(scene);
  probeRows[0].push_back(cd.time());
  for (std::size_t i = 0; i < probeNames.size(); ++i)
    probeRows[i + 1].push_back(result.probes[probeNames[i]]);
  {
    std::vector<std::string> cols{"time"};
    cols.insert(cols.end(), probeNames.begin(), probeNames.end());
    frames.writer().writeTable("probes", cols, probeRows);
    frames.writer().writeTable("energy",
                               {"time", "kinetic", "strain", "external_work", "internal_work", "mass_damping",
                                "balance_error", "dt"},
                               energyRows);
  }
  frames.writer().close();

  const EnergyLedger& E = cd.energy();
  nlohmann::json s = summaryHead(scene, result);
  const long elements = model.membranes.count + model.cables.count;
  nlohmann::json st;
  st["steps"] = steps;
  st["simulated_time"] = cd.time();
  st["wall_seconds"] = wall;
  st["element_updates_per_second"] = wall > 0 ? double(elements) * double(steps) / wall : 0.0;
  st["nodes"] = N.count;
  st["membrane_elements"] = model.membranes.count;
  st["cable_elements"] = model.cables.count;
  st["kinetic_energy"] = E.kinetic;
  st["strain_energy"] = E.strain;
  st["external_work"] = E.externalWork;
  st["internal_work"] = E.internalWork;
  st["mass_damping_dissipation"] = E.massDamping;
  st["viscous_dissipation"] = E.viscousDissipation();
  st["energy_balance_error"] = E.balanceError();
  st["last_dt"] = cd.lastDt();
  st["stable_dt"] = cd.stableDt();
  st["added_mass"] = scene.massScaling.addedMass;
  st["added_mass_fraction"] = scene.massScaling.addedFraction();
  if (tc.untilStatic) st["converged"] = result.reason == StopReason::Static;
  s["stats"] = st;
  writeSummary(s, result, opt);

  if (!opt.quiet) {
    fmt::print(
        "stop   {} after {} steps, t = {:.6g} s, {:.3g} s wall, {:.3g} M element updates/s, energy "
        "balance error {:.2e}\n",
        toString(result.reason), steps, cd.time(), wall,
        1e-6 * st["element_updates_per_second"].get<double>(), E.balanceError());
  }
  printProbesAndDiagnosis(result, opt.quiet);
  return result;
}

}  // namespace fsi::structure
