// The dynamic-relaxation run: DynamicRelaxation driven to the static state with output, probes, the residual
// history, summary.json and the stop handling it shares with the explicit run (RunCommon).
#include <fmt/format.h>

#include <chrono>

#include "structure/io/SceneFrames.hpp"
#include "structure/run/InstabilityDiagnosis.hpp"
#include "structure/run/RunCommon.hpp"
#include "structure/run/Simulation.hpp"

namespace fsi::structure {

namespace {

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
    std::fflush(stdout);
  }
  SceneFrames frames(scene, opt.outDir / "results.h5");
  frames.write(0.0, 0);
  DynamicRelaxation dr(model, scene.effectList(), scene.constraints, rs);
  const auto wall0 = Clock::now();
  // An interrupt already pending (Ctrl-C during set-up) stops at the first iteration, with the start state.
  const RelaxationResult r = dr.run(
      [&](int inc, const RelaxationResult& rr) {
        frames.write(double(inc) / rs.increments, rr.iterations);
        if (!opt.quiet)
          fmt::print("increment {}/{} converged: iteration {}, residual ratio {:.3g}, KE/U {:.3g}\n", inc,
                     rs.increments, rr.iterations, rr.residualRatio, rr.energyRatio);
      },
      [] { return interruptRequested(); });
  const double wall = std::chrono::duration<double>(Clock::now() - wall0).count();
  result.reason = r.converged     ? StopReason::Static
                  : r.diverged    ? StopReason::Unstable
                  : r.interrupted ? StopReason::Interrupted
                                  : StopReason::NotConverged;
  const double loadFactor = double(std::max(r.increment, 1)) / rs.increments;
  if (r.diverged) {
    // Diagnose at the diverged state, then keep the best iterate of the failing increment.
    result.diagnosis = diagnoseRelaxation(scene, dr, r);
    const RelaxationSnapshot& b = dr.best();
    if (b.iteration >= 0) {
      N.x = b.x;
      N.v = b.v;
      evaluateEffects(N, scene.effectList(), rs.loadTime, b.loadFactor, false);
      writeStopState(opt, relaxationState(N, b.iteration, b.loadFactor, b.residualRatio, b.increment),
                     result);
      if (!result.stateFile.empty()) result.diagnosis += " Saved in " + result.stateFile.string() + ".";
      frames.write(b.loadFactor, b.iteration);
    } else {
      result.diagnosis += " No iterate was finite: no state to keep.";
      frames.write(loadFactor, r.iterations);
    }
  } else if (r.interrupted) {
    result.diagnosis =
        fmt::format("stopped at iteration {} of increment {} (residual ratio {:.3g}, KE/U {:.3g})",
                    r.iterations, r.increment, r.residualRatio, r.energyRatio);
    writeStopState(opt, relaxationState(N, r.iterations, loadFactor, r.residualRatio, r.increment), result);
    if (!result.stateFile.empty()) result.diagnosis += "; state saved in " + result.stateFile.string();
    frames.write(loadFactor, r.iterations);
  } else if (!r.converged) {
    result.diagnosis = diagnoseRelaxation(scene, dr, r);
    frames.write(loadFactor, r.iterations);
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
  if (r.diverged && dr.best().iteration >= 0) {
    st["last_good_iteration"] = dr.best().iteration;
    st["last_good_residual_ratio"] = dr.best().residualRatio;
  }
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

}  // namespace fsi::structure
