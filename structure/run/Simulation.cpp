#include "structure/run/Simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "structure/elements/ElementKind.hpp"
#include "structure/elements/MembraneForces.hpp"
#include "structure/io/ResultsWriter.hpp"
#include "structure/io/SceneFrames.hpp"
#include "structure/io/StateFile.hpp"
#include "structure/run/InstabilityDiagnosis.hpp"
#include "structure/run/RunCommon.hpp"

namespace fsi::structure {

namespace {
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
        if (!haveStress) membraneStresses(model.membranes, N.x.data(), stress), haveStress = true;
        for (int e : p.triangles)
          vals.push_back(stress.principal[2 * e + (p.quantity == "min_principal" ? 1 : 0)]);
        break;
    }
    out[p.name] = reduceValues(vals, p.reduce);
  }
  return out;
}

namespace {

StateSnapshot explicitState(const CentralDifference& cd, const Nodes& N) {
  StateSnapshot s;
  s.time = cd.time();
  s.step = cd.steps();
  s.dt = cd.lastDt();
  s.x = N.x;
  s.v = N.v;
  const EnergyLedger& E = cd.energy();
  s.scalars["kinetic_energy"] = E.kinetic;
  s.scalars["strain_energy"] = E.strain;
  s.scalars["external_work"] = E.externalWork;
  s.scalars["internal_work"] = E.internalWork;
  s.scalars["mass_damping_dissipation"] = E.massDamping;
  return s;
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
    std::fflush(stdout);
  }

  SceneFrames frames(scene, opt.outDir / "results.h5");
  frames.write(0.0, 0);
  std::vector<std::vector<double>> energyRows(11);
  std::vector<std::string> probeNames;
  for (const auto& p : scene.probes) probeNames.push_back(p.name);
  std::vector<std::vector<double>> probeRows(probeNames.size() + 1);

  // The last state that passed a check (its ledger too: the summary of an unstable run reports it).
  CentralDifference::Checkpoint good;
  cd.checkpoint(good);
  const double tEnd = tc.endTime;
  double nextOutput = scene.output.interval > 0 ? scene.output.interval : tEnd;
  int staticHits = 0;
  bool nonFinite = false;
  double createdAtStop = -1;  // >= 0: the check at an output or the end stopped the run
  const auto wall0 = Clock::now();
  auto lastPrint = wall0;
  bool printNow = false;

  while (true) {
    // Polled before each step, so that a request pending from the set-up (or from before the run) stops
    // at once; it is never cleared here.
    if (interruptRequested()) {
      result.reason = StopReason::Interrupted;
      break;
    }
    const double limit = std::min(nextOutput, tEnd);
    const bool monitor = (cd.steps() + 1) % tc.monitorEvery == 0;
    if (!cd.step(limit, monitor)) {
      nonFinite = true;
      result.reason = StopReason::Unstable;
      break;
    }
    // Every step (a few flops on the sums the step gathered): energy growth (an unstable step) and the
    // bookkeeping balance, so that no run, however short, and no output or end of run escapes them; on
    // monitoring steps, where the strain energy is known, also the energy created in the elements.
    const EnergyLedger& E = cd.energy();
    const double err = E.balanceError(), growth = E.growth(), created = monitor ? E.createdLast : 0.0;
    const bool unstable =
        !(growth <= kGrowthLimit) || !(err <= tc.energyTolerance) || !(created <= tc.energyTolerance);
    if (monitor || unstable) {
      for (auto [i, v] : {std::pair{0, cd.time() - cd.lastDt()},  // the energies are those of step n
                          {1, E.kinetic},
                          {2, E.strain},
                          {3, E.externalWork},
                          {4, E.internalWork},
                          {5, E.massDamping},
                          {6, err},
                          {7, cd.lastDt()},
                          {8, E.kineticProduct},
                          {9, growth},
                          {10, created}})
        energyRows[i].push_back(v);
    }
    if (unstable) {
      result.reason = StopReason::Unstable;
      break;
    }
    if (monitor) {
      cd.checkpoint(good);
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
    const bool atEnd = cd.time() >= tEnd * (1 - 1e-12);
    // At every output and at the end, the energy created in the elements is checked whatever the monitoring
    // interval (a short run, or one ended between monitoring steps, would otherwise skip it).
    if ((atOutput && scene.output.interval > 0) || atEnd) {
      const double c = cd.createdAtCurrentState();
      if (!(c <= tc.energyTolerance)) {
        createdAtStop = c;
        result.reason = StopReason::Unstable;
        break;
      }
    }
    if (atOutput && scene.output.interval > 0 && !atEnd) {
      frames.write(cd.time(), cd.steps());
      auto probes = evaluateProbes(scene);
      probeRows[0].push_back(cd.time());
      for (std::size_t i = 0; i < probeNames.size(); ++i) probeRows[i + 1].push_back(probes[probeNames[i]]);
      nextOutput += scene.output.interval;
      printNow = true;  // a progress line per output frame too (throttled below), so short runs show progress
    }
    if (atEnd) {
      result.reason = tc.untilStatic ? StopReason::NotConverged : StopReason::EndTime;
      break;
    }
    if (!opt.quiet && (printNow || (cd.steps() & 255) == 0)) {
      const auto now = Clock::now();
      const double since = std::chrono::duration<double>(now - lastPrint).count();
      if (since >= opt.progressSeconds || (printNow && since >= 0.02 * opt.progressSeconds)) {
        lastPrint = now;
        const double wall = std::chrono::duration<double>(now - wall0).count();
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
    result.diagnosis = diagnoseInstability(scene, cd, good.steps, good.time, nonFinite, createdAtStop);
    // Keep the last good state: on disk as a restartable state and as the last frame of the results.
    cd.restore(good);
    cd.evaluateForces(true);
    writeStopState(opt, explicitState(cd, N), result);
    if (!result.stateFile.empty()) result.diagnosis += " Saved in " + result.stateFile.string() + ".";
  } else {
    cd.evaluateForces(true);  // current forces for reactions, current strain energy for the summary
    if (result.reason == StopReason::Interrupted) {
      writeStopState(opt, explicitState(cd, N), result);
      result.diagnosis =
          steps == 0 ? fmt::format("stopped during set-up, before the first step (t = {:.6g} s)", cd.time())
                     : fmt::format("stopped at step {} (t = {:.6g} s)", steps, cd.time());
      result.diagnosis += result.stateFile.empty() ? "; the state could not be saved"
                                                   : "; state saved in " + result.stateFile.string();
    }
  }
  frames.write(cd.time(), cd.steps());
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
                                "balance_error", "dt", "kinetic_product", "energy_growth", "energy_created"},
                               energyRows);
  }
  frames.writer().close();

  const EnergyLedger& E = cd.energy();
  nlohmann::json s = summaryHead(scene, result);
  long elements = 0;  // element updates per step, every kind
  for (const ElementKind* kind : elementKinds()) elements += kind->count(model);
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
  st["energy_error_physical"] = E.physicalBalanceError();
  st["energy_growth_max"] = E.maxGrowth;
  st["energy_created_max"] = E.maxCreated;
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
