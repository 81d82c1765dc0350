// The dynamic-relaxation run: DynamicRelaxation driven to the static state, with what it shares with the
// explicit run around its loop (RunCommon): output series, stop handling, summary.json.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "structure/model/Error.hpp"
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

// Nothing to relax: no load at load_time, no strain at the start, nothing prescribed. A load whose time
// function starts at 0 (smooth_step, ramp: the explicit examples') is zero at the default load_time 0, and
// the relaxation would iterate to max_iterations on a residual of 0/0. A located input error instead.
void requireSomethingToRelax(Scene& scene) {
  if (!scene.constraints.prescribed.empty()) return;
  Nodes& N = scene.model->nodes;
  const double loadTime = scene.solver.relaxation.loadTime;
  evaluateEffects(N, scene.effectList(), loadTime, 1.0, false);
  double fext = 0, fint = 0;
  for (std::size_t d = 0; d < N.fext.size(); ++d) {
    fext = std::max(fext, std::abs(N.fext[d]));
    fint = std::max(fint, std::abs(N.fint[d]));
  }
  std::fill(N.fext.begin(), N.fext.end(), 0.0);
  std::fill(N.fint.begin(), N.fint.end(), 0.0);
  if (fext == 0 && fint == 0)
    throw InputError(fmt::format(
        "{}: solver.load_time {:g}: nothing to relax: every load is zero at that time, the structure starts "
        "unstrained and no motion is prescribed (a load's time function that starts at 0, like smooth_step "
        "or ramp, is 0 at load_time 0: set solver.load_time to a time where the load is on, e.g. its "
        "duration, or drop the function in a relaxation scene)",
        scene.file.string(), loadTime));
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
    fmt::print("model  {}; dynamic relaxation {} (λ = {:.3g}), ε = {:.3g}, {} increment(s)\n",
               modelCounts(model), scene.solver.method, rs.lambda > 0 ? rs.lambda : defaultLambda(rs),
               rs.tolerance, rs.increments);
    std::fflush(stdout);
  }
  requireSomethingToRelax(scene);
  if (!opt.quiet && !hasSupport(scene.constraints))
    fmt::print(
        "warning: no node is held (no fix, prescribe or slide constraint): the structure has rigid-body "
        "modes, and a load that does not balance itself moves it instead of deforming it\n");
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
  addElementKindStats(model, N.x.data(), st);
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
