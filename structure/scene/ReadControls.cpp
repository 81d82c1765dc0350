#include "structure/scene/ReadControls.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "structure/effects/Threads.hpp"
#include "structure/integrate/FictitiousMass.hpp"
#include "structure/scene/JoinNames.hpp"

namespace fsi::structure {

SolverControl readSolver(const YamlMap& top) {
  SolverControl solver;
  if (top.has("solver")) {
    YamlMap sv = top.map("solver");
    const std::string type =
        sv.choice("type", {"explicit_dynamics", "dynamic_relaxation"}, "explicit_dynamics");
    solver.threads = int(sv.integer("threads", 1, {1, 1024}));
    if (solver.threads > 1 && !threadsAvailable())
      sv.failAt("threads",
                "this build has no OpenMP (built with FSI_OPENMP=OFF or without compiler support): "
                "only 1 is possible");
    if (type == "dynamic_relaxation") {
      SolverControl& sc = solver;
      RelaxationSettings& rs = sc.relaxation;
      sc.type = SolverControl::Type::DynamicRelaxation;
      const std::string damping = sv.choice("damping", {"kinetic", "viscous"}, "kinetic");
      rs.damping =
          damping == "kinetic" ? RelaxationSettings::Damping::Kinetic : RelaxationSettings::Damping::Viscous;
      const std::string mass = sv.choice("mass", fictitiousMassRuleNames(), toString(rs.mass));
      rs.mass = fictitiousMassRuleFromName(mass);
      const std::string coef = sv.choice("coefficient", {"underwood", "rezaiee_pajand"}, "underwood");
      rs.coefficient = coef == "underwood" ? RelaxationSettings::Coefficient::Underwood
                                           : RelaxationSettings::Coefficient::RezaiePajand;
      // Unset (0 inside RelaxationSettings) takes the rule's default; `lambda: 0` is an error, not "unset".
      if (sv.has("lambda")) rs.lambda = sv.positive("lambda");
      rs.backstep = sv.boolean("backstep", true);
      rs.tolerance = sv.number("tolerance", 1e-3);
      if (!isPositiveNormal(rs.tolerance)) sv.failAt("tolerance", kPositiveRule);
      rs.maxIterations = sv.integer("max_iterations", 200000, {1, std::numeric_limits<long>::max()});
      if (rs.maxIterations < 1) sv.failAt("max_iterations", "must be >= 1");
      rs.increments = int(sv.integer("increments", 1, {1, std::numeric_limits<int>::max()}));
      if (rs.increments < 1) sv.failAt("increments", "must be >= 1");
      rs.loadTime = sv.number("load_time", 0.0);
      rs.autoMass = sv.boolean("auto_mass", true);
      rs.updateMasses = sv.boolean("update_masses", false);
      rs.threads = solver.threads;
      sv.finish({"type", "threads", "damping", "mass", "coefficient", "lambda", "backstep", "tolerance",
                 "max_iterations", "increments", "load_time", "auto_mass", "update_masses"});
      if (rs.damping == RelaxationSettings::Damping::Kinetic)
        sc.method = rs.mass == FictitiousMassRule::StressBound   ? "KDR1"
                    : rs.mass == FictitiousMassRule::Gerschgorin ? "KDR"
                                                                 : "KDR-RP";
      else
        sc.method = std::string(rs.mass == FictitiousMassRule::RezaiePajand ? "m" : "o") +
                    (rs.coefficient == RelaxationSettings::Coefficient::RezaiePajand ? "dDR" : "DR");
    } else {
      sv.finish({"type", "threads"});
    }
  }
  return solver;
}

TimeControl readTime(const YamlMap& top, bool relaxation) {
  TimeControl time;
  if (relaxation) {
    if (top.has("time")) top.failAt("time", "a dynamic-relaxation scene has no time control (see 'solver')");
  } else if (!top.has("time") && top.has("coupling")) {
    // The structural side of a coupled run: the flow solver sets the end; the step is automatic.
    time.endTime = std::numeric_limits<double>::infinity();
  } else {
    YamlMap t = top.map("time");
    TimeControl& tc = time;
    if (t.has("until_static")) {
      YamlMap s = t.map("until_static");
      tc.untilStatic = true;
      tc.staticTolerance = s.number("tolerance", 1e-8);
      tc.endTime = s.number("max_time");
      s.finish({"tolerance", "max_time"});
      if (!isPositiveNormal(tc.staticTolerance)) s.failAt("tolerance", kPositiveRule);
      if (t.has("end")) t.failAt("end", "give either 'end' or 'until_static', not both");
    } else if (top.has("coupling") && !t.has("end")) {
      tc.endTime = std::numeric_limits<double>::infinity();  // set by the flow solver
    } else {
      tc.endTime = t.number("end");
    }
    if (!(tc.endTime > 0) || (std::isfinite(tc.endTime) && !isPositiveNormal(tc.endTime)))
      t.fail("the end time (or until_static.max_time) must be > 0 and at least 2.2e-308");
    tc.integrator.safety = t.number("safety", 0.9);
    if (!(tc.integrator.safety > 0 && tc.integrator.safety <= 1.0)) t.failAt("safety", "must be in (0, 1]");
    tc.integrator.fixedDt = t.number("fixed_dt", 0.0);
    if (tc.integrator.fixedDt != 0 && !isPositiveNormal(tc.integrator.fixedDt))
      t.failAt("fixed_dt", std::string(kPositiveRule) + " (or absent for the automatic step)");
    tc.integrator.maxDt = t.number("max_dt", 1e300);
    if (!isPositiveNormal(tc.integrator.maxDt)) t.failAt("max_dt", kPositiveRule);
    tc.monitorEvery = t.integer("monitor_every", 100, {1, std::numeric_limits<long>::max()});
    if (tc.monitorEvery < 1) t.failAt("monitor_every", "must be >= 1");
    tc.energyTolerance = t.number("energy_tolerance", 0.05);
    if (!isPositiveNormal(tc.energyTolerance)) t.failAt("energy_tolerance", kPositiveRule);
    tc.massScalingMinDt = t.number("mass_scaling_min_dt", 0.0);
    if (tc.massScalingMinDt < 0) t.failAt("mass_scaling_min_dt", "must be >= 0");
    t.finish({"end", "until_static", "safety", "fixed_dt", "max_dt", "monitor_every", "energy_tolerance",
              "mass_scaling_min_dt"});
  }
  return time;
}

OutputControl readOutput(const YamlMap& top) {
  OutputControl output;
  if (top.has("output")) {
    YamlMap o = top.map("output");
    output.interval = o.number("interval", 0.0);
    if (output.interval < 0) o.failAt("interval", "must be >= 0");
    if (output.interval > 0 && !std::isnormal(output.interval))
      o.failAt("interval", "must be 0 (every step) or at least 2.2e-308 (a subnormal interval is no time)");
    if (o.has("fields")) {
      for (const auto& f : o.strings("fields")) {
        const auto& all = allOutputFields();
        if (std::find(all.begin(), all.end(), f) == all.end()) {
          const std::string near = closestMatch(f, all);
          o.failAt("fields", fmt::format("unknown field '{}'{}; valid: {}", f,
                                         near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near),
                                         joinNames(all)));
        }
        output.fields.insert(f);
      }
    } else {
      output.fields.insert(allOutputFields().begin(), allOutputFields().end());
    }
    o.finish({"interval", "fields"});
  }

  if (output.fields.empty() && !top.has("output"))
    output.fields.insert(allOutputFields().begin(), allOutputFields().end());
  return output;
}

}  // namespace fsi::structure
