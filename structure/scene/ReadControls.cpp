#include "structure/scene/ReadControls.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "structure/effects/Threads.hpp"
#include "structure/integrate/FictitiousMass.hpp"
#include "structure/scene/JoinNames.hpp"
#include "structure/scene/SceneSchema.hpp"

namespace fsi::structure {

namespace {

constexpr KeyBound kAboveZero{0, false};
constexpr double kIntMax = std::numeric_limits<int>::max();

}  // namespace

const SchemaSection& solverSchema() {
  using T = KeyType;
  static const SchemaSection s{
      "solver",
      "explicit dynamics (the default) or dynamic relaxation (docs/DYNAMIC_RELAXATION.md)",
      {{"type",
        T::Choice,
        "",
        "explicit_dynamics",
        "",
        {},
        {},
        {"explicit_dynamics", "dynamic_relaxation"},
        "the solver"},
       {"threads",
        T::Integer,
        "",
        "1",
        "",
        incl(1),
        incl(1024),
        {},
        "threads of the force evaluation and node sweeps (OpenMP builds)"}}};
  return s;
}

const SchemaSection& relaxationSchema() {
  using T = KeyType;
  static const SchemaSection s{
      "solver (type: dynamic_relaxation)",
      "dynamic relaxation to the static state (docs/DYNAMIC_RELAXATION.md)",
      {solverSchema().keys[0],
       solverSchema().keys[1],
       {"damping",
        T::Choice,
        "",
        "kinetic",
        "",
        {},
        {},
        {"kinetic", "viscous"},
        "kinetic or viscous damping"},
       {"mass",
        T::Choice,
        "",
        toString(RelaxationSettings{}.mass),
        "",
        {},
        {},
        fictitiousMassRuleNames(),
        "the fictitious mass rule"},
       {"coefficient",
        T::Choice,
        "",
        "underwood",
        "",
        {},
        {},
        {"underwood", "rezaiee_pajand"},
        "the viscous damping coefficient's rule"},
       {"lambda",
        T::Number,
        "-",
        "",
        "unset: the mass rule's",
        kAboveZero,
        {},
        {},
        "the fictitious mass factor"},
       {"backstep",
        T::Boolean,
        "",
        "true",
        "",
        {},
        {},
        {},
        "kinetic damping: restart from the kinetic-energy peak"},
       {"tolerance", T::Number, "-", "1e-3", "", kAboveZero, {}, {}, "the residual that counts as converged"},
       {"max_iterations", T::Integer, "", "200000", "", incl(1), kAnyLong, {}, "iterations before giving up"},
       {"increments", T::Integer, "", "1", "", incl(1), incl(kIntMax), {}, "load increments"},
       {"load_time",
        T::Number,
        "s",
        "0",
        "",
        {},
        {},
        {},
        "the time at which the time functions of the loads are evaluated"},
       {"auto_mass", T::Boolean, "", "true", "", {}, {}, {}, "rebuild the masses when the iteration stalls"},
       {"update_masses", T::Boolean, "", "false", "", {}, {}, {}, "rebuild the masses every restart"}}};
  return s;
}

const SchemaSection& timeSchema() {
  using T = KeyType;
  static const SchemaSection s{
      "time",
      "explicit dynamics' end and step control",
      {{"end",
        T::Number,
        "s",
        "",
        "required (unless until_static, or coupled: the flow's)",
        kAboveZero,
        {},
        {},
        "end time"},
       {"until_static",
        T::Map,
        "",
        "",
        "",
        {},
        {},
        {},
        "run until the kinetic energy settles instead of to `end` (keys below)"},
       {"safety", T::Number, "-", "0.9", "", kAboveZero, incl(1), {}, "the step over the stable step"},
       {"fixed_dt",
        T::Number,
        "s",
        "0",
        "",
        incl(0),
        {},
        {},
        "a fixed step; 0: the automatic step (a positive step at least 2.2e-308)"},
       {"max_dt", T::Number, "s", "1e300", "", kAboveZero, {}, {}, "largest automatic step"},
       {"monitor_every", T::Integer, "", "100", "", incl(1), kAnyLong, {}, "steps between energy checks"},
       {"energy_tolerance",
        T::Number,
        "-",
        "0.05",
        "",
        kAboveZero,
        {},
        {},
        "energy created in the elements over the work done that stops the run as unstable"},
       {"mass_scaling_min_dt",
        T::Number,
        "s",
        "0",
        "",
        incl(0),
        {},
        {},
        "scale the mass of elements whose step is below this; 0: no mass scaling"}}};
  return s;
}

const SchemaSection& untilStaticSchema() {
  using T = KeyType;
  static const SchemaSection s{
      "time.until_static",
      "stop when the kinetic energy over the strain energy falls below a tolerance",
      {{"tolerance", T::Number, "-", "1e-8", "", kAboveZero, {}, {}, "KE/U that counts as static"},
       {"max_time", T::Number, "s", "", "required", kAboveZero, {}, {}, "end time if it never settles"}}};
  return s;
}

const SchemaSection& outputSchema() {
  using T = KeyType;
  static const SchemaSection s{
      "output",
      "frames of results.h5 / results.xdmf",
      {{"interval",
        T::Number,
        "s",
        "0",
        "",
        incl(0),
        {},
        {},
        "time between frames; 0: every step (a positive interval at least 2.2e-308)"},
       {"fields", T::Strings, "", "", "all", {}, {}, allOutputFields(), "the fields written"}}};
  return s;
}

SolverControl readSolver(const YamlMap& top) {
  SolverControl solver;
  if (top.has("solver")) {
    YamlMap svMap = top.map("solver");
    const SchemaMap sv(svMap, solverSchema());
    const std::string type = sv.string("type");
    solver.threads = int(sv.integer("threads"));
    if (solver.threads > 1 && !threadsAvailable())
      svMap.failAt("threads",
                   "this build has no OpenMP (built with FSI_OPENMP=OFF or without compiler support): "
                   "only 1 is possible");
    if (type == "dynamic_relaxation") {
      const SchemaMap dr(svMap, relaxationSchema());
      SolverControl& sc = solver;
      RelaxationSettings& rs = sc.relaxation;
      sc.type = SolverControl::Type::DynamicRelaxation;
      rs.damping = dr.string("damping") == "kinetic" ? RelaxationSettings::Damping::Kinetic
                                                     : RelaxationSettings::Damping::Viscous;
      rs.mass = fictitiousMassRuleFromName(dr.string("mass"));
      rs.coefficient = dr.string("coefficient") == "underwood"
                           ? RelaxationSettings::Coefficient::Underwood
                           : RelaxationSettings::Coefficient::RezaiePajand;
      // Unset (0 inside RelaxationSettings) takes the rule's default; `lambda: 0` is an error, not "unset".
      if (dr.has("lambda")) rs.lambda = dr.number("lambda");
      rs.backstep = dr.boolean("backstep");
      rs.tolerance = dr.number("tolerance");
      rs.maxIterations = dr.integer("max_iterations");
      rs.increments = int(dr.integer("increments"));
      rs.loadTime = dr.number("load_time");
      rs.autoMass = dr.boolean("auto_mass");
      rs.updateMasses = dr.boolean("update_masses");
      rs.threads = solver.threads;
      dr.finish();
      if (rs.damping == RelaxationSettings::Damping::Kinetic)
        sc.method = rs.mass == FictitiousMassRule::StressBound   ? "KDR1"
                    : rs.mass == FictitiousMassRule::Gerschgorin ? "KDR"
                                                                 : "KDR-RP";
      else
        sc.method = std::string(rs.mass == FictitiousMassRule::RezaiePajand ? "m" : "o") +
                    (rs.coefficient == RelaxationSettings::Coefficient::RezaiePajand ? "dDR" : "DR");
    } else {
      sv.finish();
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
    YamlMap tMap = top.map("time");
    const SchemaMap t(tMap, timeSchema());
    TimeControl& tc = time;
    if (t.has("until_static")) {
      YamlMap sMap = tMap.map("until_static");
      const SchemaMap s(sMap, untilStaticSchema());
      tc.untilStatic = true;
      tc.staticTolerance = s.number("tolerance");
      tc.endTime = s.number("max_time");
      s.finish();
      if (t.has("end")) tMap.failAt("end", "give either 'end' or 'until_static', not both");
    } else if (top.has("coupling") && !t.has("end")) {
      tc.endTime = std::numeric_limits<double>::infinity();  // set by the flow solver
    } else {
      if (!t.has("end")) tMap.required("end");  // the located "missing required key"
      tc.endTime = t.number("end");
    }
    tc.integrator.safety = t.number("safety");
    tc.integrator.fixedDt = t.number("fixed_dt");
    if (tc.integrator.fixedDt != 0 && !isPositiveNormal(tc.integrator.fixedDt))
      tMap.failAt("fixed_dt", std::string(kPositiveRule) + " (or absent for the automatic step)");
    tc.integrator.maxDt = t.number("max_dt");
    tc.monitorEvery = t.integer("monitor_every");
    tc.energyTolerance = t.number("energy_tolerance");
    tc.massScalingMinDt = t.number("mass_scaling_min_dt");
    t.finish();
  }
  return time;
}

OutputControl readOutput(const YamlMap& top) {
  OutputControl output;
  if (top.has("output")) {
    YamlMap oMap = top.map("output");
    const SchemaMap o(oMap, outputSchema());
    output.interval = o.number("interval");
    if (output.interval > 0 && !std::isnormal(output.interval))
      oMap.failAt("interval",
                  "must be 0 (every step) or at least 2.2e-308 (a subnormal interval is no time)");
    if (o.has("fields")) {
      const std::vector<std::string>& all = o.section().key("fields").choices;
      for (const auto& f : oMap.strings("fields")) {
        if (std::find(all.begin(), all.end(), f) == all.end()) {
          const std::string near = closestMatch(f, all);
          oMap.failAt("fields", fmt::format("unknown field '{}'{}; valid: {}", f,
                                            near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near),
                                            joinNames(all)));
        }
        output.fields.insert(f);
      }
    } else {
      output.fields.insert(allOutputFields().begin(), allOutputFields().end());
    }
    o.finish();
  }

  if (output.fields.empty() && !top.has("output"))
    output.fields.insert(allOutputFields().begin(), allOutputFields().end());
  return output;
}

}  // namespace fsi::structure
