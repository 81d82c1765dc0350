#include "structure/run/Simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "structure/elements/ElementKind.hpp"
#include "structure/run/InstabilityDiagnosis.hpp"
#include "structure/run/RunCommon.hpp"

namespace fsi::structure {

// evaluateProbes: structure/run/EvaluateProbes.cpp.

namespace {

// The state an explicit run keeps when it stops, with its energies for whoever reads the file.
StateSnapshot explicitState(const CentralDifference& cd) {
  StateSnapshot s = cd.checkpoint();
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
  std::filesystem::create_directories(opt.outDir);
  Model& model = *scene.model;
  Nodes& N = model.nodes;
  const TimeControl& tc = scene.time;
  CentralDifference cd(model, scene.effectList(), scene.constraints, tc.integrator);
  RunResult result;
  if (opt.startState) {
    // A continued run (--start-from STATE.h5): the state's time, step count and last step, its positions
    // and mid-step velocities; the energy bookkeeping starts again at it.
    const StateSnapshot& s = *opt.startState;
    if (s.x.size() != N.x.size() || s.v.size() != N.v.size())
      throw std::invalid_argument(
          fmt::format("runSimulation: start state of {} nodes for a model of {}", s.x.size() / 3, N.count));
    cd.restore(s.x, s.v, s.time, s.dt, s.step);
  }
  const double startTime = cd.time();
  const long startStep = cd.steps();

  if (!opt.quiet) {
    printSceneLine(scene);
    fmt::print("model  {}; effects: ", modelCounts(model));
    for (std::size_t i = 0; i < scene.enabledEffects.size(); ++i)
      fmt::print("{}{}", i ? ", " : "", scene.enabledEffects[i]);
    fmt::print("\n");
    if (scene.massScaling.scaledElements > 0)
      fmt::print("mass scaling: {} elements, added mass {:.4g} kg ({:.3g}% of {:.4g} kg)\n",
                 scene.massScaling.scaledElements, scene.massScaling.addedMass,
                 100 * scene.massScaling.addedFraction(), scene.massScaling.physicalMass);
    std::fflush(stdout);
  }

  RunOutput output(scene, opt);
  std::vector<std::vector<double>> energyRows(11);

  // The last state that passed a check (its ledger too: the summary of an unstable run reports it).
  StateSnapshot good;
  cd.checkpoint(good);
  const double tEnd = tc.endTime;
  double nextOutput = scene.output.interval > 0 ? scene.output.interval : tEnd;
  // A continued run: the output times the run it continues had still ahead (summed as it summed them).
  while (scene.output.interval > 0 && cd.time() > 0 && cd.time() >= nextOutput * (1 - 1e-12))
    nextOutput += scene.output.interval;
  int staticHits = 0;
  bool nonFinite = false;
  double createdAtStop = -1;  // >= 0: the check at an output or the end stopped the run
  RunClock clock(opt.progressSeconds);
  bool printNow = false;

  while (true) {
    // Polled before each step, so that a request pending from the set-up (or from before the run) stops
    // at once; it is never cleared here.
    if (stopRequested(opt)) {
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
      output.frame(cd.time(), cd.steps());
      output.probeRow(cd.time(), evaluateProbes(scene));
      nextOutput += scene.output.interval;
      printNow = true;  // a progress line per output frame too (throttled), so short runs show progress
    }
    if (atEnd) {
      result.reason = tc.untilStatic ? StopReason::NotConverged : StopReason::EndTime;
      break;
    }
    if (!opt.quiet && (printNow || (cd.steps() & 255) == 0)) {  // the clock read every 256 steps at most
      if (clock.progressDue(printNow)) {
        const double eta = clock.seconds() * (tEnd - cd.time()) / std::max(cd.time() - startTime, 1e-300);
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
  const double wall = clock.seconds();
  const long steps = cd.steps();
  const long stepsRun = steps - startStep;  // a continued run counts from the state's step

  if (result.reason == StopReason::Unstable) {
    result.diagnosis = diagnoseInstability(scene, cd, good.step, good.time, nonFinite, createdAtStop);
    // Keep the last good state: on disk as a restartable state and as the last frame of the results.
    cd.restore(good);
    cd.evaluateForces(true);
    saveStopState(opt, explicitState(cd), result);
  } else {
    cd.evaluateForces(true);  // current forces for reactions, current strain energy for the summary
    if (result.reason == StopReason::Interrupted) {
      result.diagnosis =
          stepsRun == 0
              ? fmt::format("stopped during set-up, before the first step (t = {:.6g} s)", cd.time())
              : fmt::format("stopped at step {} (t = {:.6g} s)", steps, cd.time());
      saveStopState(opt, explicitState(cd), result);
    }
  }
  output.frame(cd.time(), cd.steps());
  result.probes = evaluateProbes(scene);
  output.probeRow(cd.time(), result.probes);
  output.table("energy",
               {"time", "kinetic", "strain", "external_work", "internal_work", "mass_damping",
                "balance_error", "dt", "kinetic_product", "energy_growth", "energy_created"},
               energyRows);
  result.probeExtremes = output.extremes();
  output.close();

  const EnergyLedger& E = cd.energy();
  long elements = 0;  // element updates per step, every kind
  for (const ElementKind* kind : elementKinds()) elements += kind->count(model);
  nlohmann::json st;
  st["steps"] = steps;
  st["simulated_time"] = cd.time();
  st["wall_seconds"] = wall;
  st["element_updates_per_second"] = wall > 0 ? double(elements) * double(stepsRun) / wall : 0.0;
  st["nodes"] = N.count;
  addElementKindStats(model, N.x.data(), st);
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
  const std::string stopLine = fmt::format(
      "stop   {} after {} steps, t = {:.6g} s, {:.3g} s wall, {:.3g} M element updates/s, energy balance "
      "error {:.2e}",
      toString(result.reason), steps, cd.time(), wall, 1e-6 * st["element_updates_per_second"].get<double>(),
      E.balanceError());
  finishRun(scene, result, opt, st, stopLine);
  return result;
}

}  // namespace fsi::structure
