// The dynamic-relaxation run: DynamicRelaxation driven to the static state, with what it shares with the
// explicit run around its loop (RunCommon): output series, stop handling, summary.json.
#include <fmt/format.h>

#include "structure/run/InstabilityDiagnosis.hpp"
#include "structure/run/RunCommon.hpp"
#include "structure/run/Simulation.hpp"

namespace fsi::structure {

namespace {

// The current iterate as a state (as DynamicRelaxation::best() keeps one).
StateSnapshot relaxationState(const Nodes& N, long iteration, double loadFactor, double residualRatio,
                              int increment) {
  StateSnapshot s;
  s.time = loadFactor;  // the pseudo time of a relaxation's frames: the load factor
  s.step = iteration;
  s.dt = 1.0;
  s.x = N.x;
  s.v = N.v;
  s.scalars["residual_ratio"] = residualRatio;
  s.scalars["load_factor"] = loadFactor;
  s.scalars["increment"] = increment;
  return s;
}

}  // namespace

RunResult runRelaxation(Scene& scene, const RunOptions& opt) {
  std::filesystem::create_directories(opt.outDir);
  Model& model = *scene.model;
  Nodes& N = model.nodes;
  const RelaxationSettings& rs = scene.solver.relaxation;
  RunResult result;
  if (!opt.quiet) {
    printSceneLine(scene);
    fmt::print(
        "model  {} nodes, {} membrane triangles, {} cables; dynamic relaxation {} (λ = {:.3g}), ε = {:.3g}, "
        "{} increment(s)\n",
        N.count, model.membranes.count, model.cables.count, scene.solver.method,
        rs.lambda > 0 ? rs.lambda : defaultLambda(rs), rs.tolerance, rs.increments);
    std::fflush(stdout);
  }
  RunOutput output(scene, opt);
  DynamicRelaxation dr(model, scene.effectList(), scene.constraints, rs);
  RunClock clock(opt.progressSeconds);
  // A stop already requested (Ctrl-C during set-up) stops at the first iteration, with the start state.
  const RelaxationResult r = dr.run(
      [&](int inc, const RelaxationResult& rr) {
        output.frame(double(inc) / rs.increments, rr.iterations);
        if (!opt.quiet)
          fmt::print("increment {}/{} converged: iteration {}, residual ratio {:.3g}, KE/U {:.3g}\n", inc,
                     rs.increments, rr.iterations, rr.residualRatio, rr.energyRatio);
      },
      [&] { return stopRequested(opt); });
  const double wall = clock.seconds();
  result.reason = r.reason;
  const double loadFactor = double(std::max(r.increment, 1)) / rs.increments;
  if (r.reason == StopReason::Unstable) {
    // Diagnose at the diverged state, then keep the best iterate of the failing increment.
    result.diagnosis = diagnoseRelaxation(scene, dr, r);
    const StateSnapshot& b = dr.best();
    if (!b.empty()) {
      N.x = b.x;
      N.v = b.v;
      evaluateEffects(N, scene.effectList(), rs.loadTime, b.time, false);
      saveStopState(opt, b, result);
      output.frame(b.time, b.step);
    } else {
      result.diagnosis += " No iterate was finite: no state to keep.";
      output.frame(loadFactor, r.iterations);
    }
  } else if (r.reason == StopReason::Interrupted) {
    result.diagnosis =
        fmt::format("stopped at iteration {} of increment {} (residual ratio {:.3g}, KE/U {:.3g})",
                    r.iterations, r.increment, r.residualRatio, r.energyRatio);
    saveStopState(opt, relaxationState(N, r.iterations, loadFactor, r.residualRatio, r.increment), result);
    output.frame(loadFactor, r.iterations);
  } else if (r.reason == StopReason::NotConverged) {
    result.diagnosis = diagnoseRelaxation(scene, dr, r);
    output.frame(loadFactor, r.iterations);
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
    output.table("residual", {"iteration", "residual_ratio", "energy_ratio", "kinetic", "strain"}, cols);
  }
  output.close();

  const bool converged = r.reason == StopReason::Static;
  nlohmann::json st;
  st["solver"] = "dynamic_relaxation";
  st["method"] = scene.solver.method;
  st["lambda"] = r.lambda;
  st["iterations"] = r.iterations;
  st["converged"] = converged;
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
  if (r.reason == StopReason::Unstable && !dr.best().empty()) {
    st["last_good_iteration"] = dr.best().step;
    st["last_good_residual_ratio"] = dr.best().scalars.at("residual_ratio");
  }
  const std::string stopLine = fmt::format(
      "stop   {} after {} iterations ({} kinetic resets, {} node mass increases, {} restarts), {:.3g} s "
      "wall, "
      "{:.3g} ms per iteration, residual ratio {:.3g}, KE/U {:.3g}",
      toString(result.reason), r.iterations, r.kineticResets, r.massIncreases, r.restarts, wall,
      1e3 * st["seconds_per_iteration"].get<double>(), r.residualRatio, r.energyRatio);
  finishRun(scene, result, opt, st, stopLine);
  return result;
}

}  // namespace fsi::structure
