// fsi: the command-line front end.
//   fsi run SCENE.yaml --out DIR [--set key.path=value ...] [--quiet] [--start-from RUN | STATE.h5]
//   fsi validate CASE_DIR [--out DIR]   runs the checks in CASE_DIR/reference.yaml against their references
//   fsi map-check SRC DST [--tolerance T] [--json FILE] [--set key=value]
//                          checks the projections between two interface meshes (Gmsh file, OpenFOAM patch
//                          or a structure scene's coupling interface)
//   fsi plot RUN_DIR [--out DIR] [--color auto|stress|displacement]
//                          PNG plots of a run (share/fsi/fsi_plot.py)
//   fsi generate SCENE.yaml --out DIR [--set key.path=value ...] [--deformed RUN]
//                          writes the scene's meshes (MESH.msh with its sets, MESH.stl of the outer surface),
//                          as designed or at a run's last frame (GenerateCommand)

#include <fmt/format.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "GenerateCommand.hpp"
#include "coupling/effects/CouplingEffects.hpp"
#include "coupling/interface/SceneInterface.hpp"
#include "coupling/mapping/MapCheck.hpp"
#include "coupling/mapping/StateTransfer.hpp"
#include "flight/FlightFile.hpp"
#include "flight/FlightRun.hpp"
#include "structure/io/ResultsWriter.hpp"
#include "structure/io/StateFile.hpp"
#include "structure/model/Error.hpp"
#include "structure/run/Interrupt.hpp"
#include "structure/run/Simulation.hpp"
#include "structure/scene/Scene.hpp"
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fs = std::filesystem;
using namespace fsi::structure;

namespace {

// SIGINT and SIGTERM ask a run to stop cleanly (state and summary written, exit 130 or 143): the handler
// requests gStop, the token every run of this program gets (RunOptions::stop). A constant-initialised static,
// so it exists before any code runs. The handler is installed from the executable's pre-initialisation array,
// the first code of the program that runs — before the shared libraries' static initialisers and main() —
// so that a signal from then on is a request, never a kill. Only the dynamic loader's mapping and relocation
// of the libraries precede it (a few ms; nothing of the run exists yet): a signal then ends the process by
// its default action. Commands without a run (map-check, plot, generate) restore the default actions.
StopToken gStop;

extern "C" void fsiEarlyInterruptHandler(int, char**, char**) {
  installInterruptHandler(gStop);
}
__attribute__((section(".preinit_array"), used)) void (*const fsiPreinit)(int, char**,
                                                                          char**) = fsiEarlyInterruptHandler;

// The structural side of a coupled scene has no end time of its own (the flow solver sets it); run alone it
// would start with an infinite time to go, so it needs one given.
void requireEndTime(const Scene& scene) {
  if (scene.solver.type == SolverControl::Type::ExplicitDynamics && !std::isfinite(scene.time.endTime))
    throw fsi::InputError(
        fmt::format("{}: time.end: this coupled scene takes its end time from the flow "
                    "solver; to run the structure alone, give one (e.g. --set time.end=1.0)",
                    scene.file.string()));
}

// --start-from: the model starts at another run's last frame (results.h5), interpolated onto this mesh (a
// continuation in a load, a resumed relaxation, or a run of the same geometry on another mesh), or at a state
// file a stopped run kept (interrupted_state.h5, last_good_state.h5: startFromState). Held degrees of freedom
// stay at their reference.
nlohmann::json startFromState(Scene& scene, const fs::path& source, bool quiet, RunOptions& opt);

nlohmann::json startFromRun(Scene& scene, fs::path source, bool quiet, RunOptions& opt) {
  if (fs::is_directory(source)) source /= "results.h5";
  if (isStateFile(source)) return startFromState(scene, source, quiet, opt);
  if (scene.solver.type != fsi::structure::SolverControl::Type::DynamicRelaxation)
    throw fsi::InputError(
        fmt::format("--start-from {}: starting from a results file is only for a dynamic_relaxation scene "
                    "(solver.type); "
                    "{} runs explicit dynamics, which starts at rest in its reference state or continues "
                    "from a state file (interrupted_state.h5, last_good_state.h5)",
                    source.string(), scene.file.string()));
  fsi::structure::ResultsFrame frame;
  try {
    frame = fsi::structure::readLastFrame(source);
  } catch (const fsi::InputError& e) {
    throw fsi::InputError(fmt::format("--start-from: {}", e.what()));
  }
  fsi::coupling::StateTransferReport rep;
  const std::vector<double> u =
      fsi::coupling::transferDisplacement(frame, *scene.model, "--start-from " + source.string(), -1.0, &rep);
  auto& N = scene.model->nodes;
  for (std::size_t d = 0; d < u.size(); ++d) N.x[d] = N.X[d] + u[d];
  for (const int d : scene.constraints.fixedDofs) N.x[std::size_t(d)] = N.X[std::size_t(d)];
  std::fill(N.v.begin(), N.v.end(), 0.0);
  if (!quiet)
    fmt::print(
        "start  {} frame {} (t = {:g}, {} nodes); this model's {} nodes: {} on its triangles, {} on its "
        "cables, {} at its nearest node; largest distance {:.3g} m\n",
        source.string(), frame.step, frame.time, frame.numNodes(), N.count, rep.membraneNodes, rep.cableNodes,
        rep.pointNodes, rep.largestDistance);
  return {{"file", source.string()},
          {"kind", "results"},
          {"frame", frame.step},
          {"time", frame.time},
          {"source_nodes", frame.numNodes()},
          {"membrane_nodes", rep.membraneNodes},
          {"cable_nodes", rep.cableNodes},
          {"point_nodes", rep.pointNodes},
          {"largest_distance", rep.largestDistance}};
}

// A state file (io/StateFile) of a run of this scene, node for node (no interpolation: its node count must be
// the model's). An explicit scene continues from it — time, step, last Δt, positions, mid-step velocities —
// (an explicit run's state only: a relaxation's time is a load factor); a dynamic relaxation starts at its
// positions, at rest, from the first load increment.
nlohmann::json startFromState(Scene& scene, const fs::path& source, bool quiet, RunOptions& opt) {
  StateSnapshot s;
  try {
    s = readState(source);
  } catch (const fsi::InputError& e) {
    throw fsi::InputError(fmt::format("--start-from: {}", e.what()));
  }
  auto fail = [&](const std::string& what) {
    throw fsi::InputError(fmt::format("--start-from {}: {}", source.string(), what));
  };
  auto& N = scene.model->nodes;
  if (s.x.size() != N.x.size())
    fail(
        fmt::format("dataset /x holds the state of {} nodes, but {} builds a model of {} nodes: the state is "
                    "of another scene or mesh (give the scene, and the --set options, of the run that wrote "
                    "it)",
                    s.x.size() / 3, scene.file.string(), N.count));
  for (const auto& [name, values] : {std::pair{"/x", &s.x}, std::pair{"/v", &s.v}})
    for (std::size_t d = 0; d < values->size(); ++d)
      if (!std::isfinite((*values)[d]))
        fail(fmt::format("dataset {} holds a non-finite value (node {}, component {})", name, d / 3, d % 3));
  if (!std::isfinite(s.time)) fail(fmt::format("attribute /@time is {}", s.time));
  if (!(s.dt >= 0) || !std::isfinite(s.dt)) fail(fmt::format("attribute /@dt is {}, not a step >= 0", s.dt));
  if (s.step < 0) fail(fmt::format("attribute /@step is {}, not a step count >= 0", s.step));
  const bool relaxationState = s.scalars.count("load_factor") > 0;
  const bool explicitScene = scene.solver.type == fsi::structure::SolverControl::Type::ExplicitDynamics;
  if (explicitScene) {
    if (relaxationState)
      fail(
          fmt::format("the state of a dynamic relaxation (its time is a load factor, /scalars/load_factor) "
                      "cannot continue an explicit run; {} runs explicit dynamics",
                      scene.file.string()));
    if (!(s.time < scene.time.endTime))
      fail(fmt::format("the state is at t = {:.9g} s, not before the end of {} ({:.9g} s): nothing to run",
                       s.time, scene.file.string(), scene.time.endTime));
    if (s.step > 0 && !(s.dt > 0)) fail(fmt::format("attribute /@dt is 0 after {} steps", s.step));
    for (const int d : scene.constraints.fixedDofs) {  // (a state of this scene has them so already)
      s.x[std::size_t(d)] = N.X[std::size_t(d)];
      s.v[std::size_t(d)] = 0.0;
    }
    opt.startState = s;
  } else {
    N.x = s.x;
    for (const int d : scene.constraints.fixedDofs) N.x[std::size_t(d)] = N.X[std::size_t(d)];
    std::fill(N.v.begin(), N.v.end(), 0.0);
  }
  if (!quiet)
    fmt::print("start  {}: {} state at {} {} ({} {:g}), {} nodes{}\n", source.string(),
               relaxationState ? "relaxation" : "explicit", relaxationState ? "iteration" : "step", s.step,
               relaxationState ? "load factor" : "t =", s.time, N.count,
               explicitScene ? "; continuing" : "; its positions start the relaxation");
  return {{"file", source.string()},
          {"kind", relaxationState ? "relaxation_state" : "explicit_state"},
          {"step", s.step},
          {"time", s.time},
          {"source_nodes", s.x.size() / 3}};
}

int runCommand(const fs::path& scenePath, const fs::path& out, const std::vector<std::string>& sets,
               const fs::path& startFrom, bool quiet) {
  installInterruptHandler(gStop);  // (already installed before main; repeated in case a library replaced it)
  Scene scene = loadScene(scenePath, sets);
  requireEndTime(scene);
  RunOptions opt;
  if (!startFrom.empty()) opt.startFrom = startFromRun(scene, startFrom, quiet, opt);
  // An output directory that cannot be made is bad input too: say so before the run, not as a crash in it.
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec || !fs::is_directory(out))
    throw fsi::InputError(fmt::format("--out {}: cannot create the output directory{}", out.string(),
                                      ec ? ": " + ec.message() : ""));
  // Continued into the directory of the run that kept the state: its series goes on there.
  if (opt.startState) {
    const fs::path from = fs::path(opt.startFrom["file"].get<std::string>()).parent_path();
    opt.continueSeries = fs::equivalent(from.empty() ? fs::path(".") : from, out, ec);
  }
  opt.outDir = out;
  opt.quiet = quiet;
  opt.stop = &gStop;
  const RunResult r = runSimulation(scene, opt);
  if (!quiet)
    fmt::print("results {}/results.xdmf (open in ParaView), summary {}/summary.json\n", out.string(),
               out.string());
  return r.exitCode();
}

int validateCommand(const fs::path& caseDir, fs::path out, bool quiet) {
  const fs::path refFile = caseDir / "reference.yaml";
  if (!fs::exists(refFile)) throw fsi::InputError(fmt::format("{}: no such file", refFile.string()));
  std::ifstream in(refFile);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) throw fsi::InputError(fmt::format("{}: cannot read", refFile.string()));
  const YAML::Node root = parseDocument(text.str(), refFile.string());
  checkDocument(root, refFile.string());
  YamlMap top(root, refFile.string(), "");
  const std::string source = top.string("reference");
  const YAML::Node checks = top.raw("checks");
  top.finish({"reference", "checks"});
  if (!checks || !checks.IsSequence() || checks.size() == 0) top.fail("'checks' must be a non-empty list");
  // Not results/<case>: that is where README's `fsi run ... --out results/<case>` writes a case's own run.
  if (out.empty()) {
    fs::path name = fs::absolute(caseDir).lexically_normal();
    if (name.filename().empty()) name = name.parent_path();
    out = fs::path("results") / "validate" / name.filename();
  }
  std::size_t failures = 0;
  fmt::print("validate {}  (reference: {})\n", caseDir.string(), source);
  fmt::print("  {:<34} {:>14} {:>14} {:>9} {:>8}  {}\n", "check", "computed", "expected", "error", "tol", "");
  std::size_t total = 0;
  std::map<std::string, std::map<std::string, double>> earlier;  // probes of the checks run, by label
  for (std::size_t i = 0; i < checks.size(); ++i) {
    YamlMap c(checks[i], refFile.string(), fmt::format("checks[{}]", i));
    const std::string label = c.string("label");
    const std::string sceneName = c.string("scene");
    std::vector<std::string> sets;
    if (c.has("set")) sets = c.strings("set");
    YamlMap expects = c.map("expect");
    c.finish({"label", "scene", "set", "expect"});
    Scene scene = loadScene(caseDir / sceneName, sets);
    requireEndTime(scene);
    RunOptions opt;
    opt.outDir = out / fmt::format("check{}", i);
    opt.quiet = quiet;
    opt.stop = &gStop;  // a request stops this run and, below, every remaining one
    const RunResult r = runSimulation(scene, opt);
    if (r.reason == StopReason::Interrupted) {
      fmt::print("interrupted: the remaining checks were not run\n");
      return r.exitCode();
    }
    for (const std::string& probe : expects.keys()) {
      YamlMap e = expects.map(probe);
      // The expected value, one of: `value` (an analytic or published reference), `equal_to: OTHER` —
      // another probe of the same run (a symmetry or balance that must hold whatever the values are), or
      // `baseline: LABEL` — the same probe in an earlier check (what a change must leave unchanged).
      const int given = int(e.has("value")) + int(e.has("equal_to")) + int(e.has("baseline"));
      if (given != 1)
        e.fail(
            "give exactly one of 'value' (a number), 'equal_to' (a probe) or 'baseline' (an earlier check)");
      const auto it = r.probes.find(probe);
      if (it == r.probes.end()) expects.failAt(probe, fmt::format("the scene defines no probe '{}'", probe));
      double value = 0;
      std::string against;
      if (e.has("value")) {
        value = e.number("value");
      } else if (e.has("equal_to")) {
        against = " = " + e.string("equal_to");
        const auto ot = r.probes.find(e.string("equal_to"));
        if (ot == r.probes.end())
          e.failAt("equal_to", fmt::format("the scene defines no probe '{}'", e.string("equal_to")));
        value = ot->second;
      } else {
        // `of: PROBE` compares with another probe of the earlier check and `factor: F` scales it: a mirror
        // image (the left brake against the right: left tension vs right tension, yaw and roll with factor
        // -1)
        const std::string base = e.string("baseline");
        const std::string of = e.has("of") ? e.string("of") : probe;
        against = " vs " + base + (of != probe ? " " + of : "");
        const auto bt = earlier.find(base);
        if (bt == earlier.end())
          e.failAt("baseline",
                   fmt::format("no earlier check is labelled '{}' (a baseline runs before the check "
                               "that compares with it)",
                               base));
        const auto pt = bt->second.find(of);
        if (pt == bt->second.end())
          e.failAt(e.has("of") ? "of" : "baseline",
                   fmt::format("the check '{}' has no probe '{}'", base, of));
        value = pt->second;
      }
      if (e.has("factor")) {
        if (!e.has("baseline"))
          e.failAt("factor", "'factor' scales a 'baseline' (give 'value' scaled instead)");
        const double f = e.number("factor");
        value *= f;
        if (f != 1.0) against += fmt::format(" x {:g}", f);
      }
      if (e.has("of") && !e.has("baseline")) e.failAt("of", "'of' names the probe of a 'baseline' check");
      const double relTol = e.number("rel_tol");
      e.finish({"value", "equal_to", "baseline", "of", "factor", "rel_tol"});
      if (!(relTol >= 0)) e.failAt("rel_tol", "must be >= 0");
      // Relative error; for an expected 0 the tolerance is absolute (and shown as such, not as a percentage).
      const bool absolute = value == 0.0;
      const double err = std::abs(it->second - value) / (absolute ? 1.0 : std::abs(value));
      const bool ok = r.exitCode() == 0 && err <= relTol;
      failures += ok ? 0 : 1;
      ++total;
      const std::string errText =
          absolute ? fmt::format("{:>9.3g}", err) : fmt::format("{:>8.3f}%", 100 * err);
      const std::string tolText =
          absolute ? fmt::format("{:>8.3g}", relTol) : fmt::format("{:>7.2f}%", 100 * relTol);
      fmt::print("  {:<34} {:>14.7g} {:>14.7g} {} {}  {}{}{}\n", label + ": " + probe + against, it->second,
                 value, errText, tolText, ok ? "ok" : "FAIL",
                 absolute ? " (absolute: the expected value is 0)" : "",
                 r.exitCode() ? " (" + toString(r.reason) + ")" : "");
    }
    earlier[label] = r.probes;
  }
  fmt::print("{} of {} checks passed\n", total - failures, total);
  return failures == 0 ? 0 : 1;
}

// The map-check options as written on the command line; every default is the coupled run's
// (fsi::coupling::coupledRunProjection(), also the adapter's option table's).
struct MapCheckArgs {
  std::string variant, level, evaluation, gapCorrection, defect, keepSide;
};

bool yesNoArg(const std::string& flag, const std::string& value) {
  if (value == "yes") return true;
  if (value == "no") return false;
  throw fsi::InputError(fmt::format("{} {}: must be yes or no", flag, value));
}

fsi::coupling::ProjectionOptions mapCheckProjection(const MapCheckArgs& args) {
  fsi::coupling::ProjectionOptions po = fsi::coupling::coupledRunProjection();
  if (args.level == "auto") {
    po.quadratureLevel = fsi::coupling::kAutoQuadrature;
  } else {
    char* end = nullptr;
    errno = 0;
    const long level = std::strtol(args.level.c_str(), &end, 10);
    if (args.level.empty() || *end != '\0' || errno == ERANGE || level < 1 ||
        level > fsi::coupling::kMaxQuadratureLevel)
      throw fsi::InputError(fmt::format("--quadrature-level {}: must be auto or an integer from 1 to {}",
                                        args.level, fsi::coupling::kMaxQuadratureLevel));
    po.quadratureLevel = int(level);
  }
  if (!fsi::coupling::massMatrixFromName(args.variant, po.mass))
    throw fsi::InputError(fmt::format("--variant {}: must be one of {}", args.variant,
                                      fmt::join(fsi::coupling::massMatrixNames(), ", ")));
  if (args.evaluation == "pointwise")
    po.evaluation = fsi::coupling::ProjectionOptions::Evaluation::Pointwise;
  else if (args.evaluation == "l2")
    po.evaluation = fsi::coupling::ProjectionOptions::Evaluation::L2;
  else
    throw fsi::InputError(fmt::format("--evaluation {}: must be pointwise or l2", args.evaluation));
  po.gapCorrection = yesNoArg("--gap-correction", args.gapCorrection);
  po.keepSide = yesNoArg("--keep-side", args.keepSide);
  if (args.defect == "auto")
    po.defectCorrection = fsi::coupling::ProjectionOptions::Defect::Auto;
  else if (args.defect == "on")
    po.defectCorrection = fsi::coupling::ProjectionOptions::Defect::On;
  else if (args.defect == "off")
    po.defectCorrection = fsi::coupling::ProjectionOptions::Defect::Off;
  else
    throw fsi::InputError(fmt::format("--defect-correction {}: must be auto, on or off", args.defect));
  return po;
}

// Exit code 0 when every point mapped, 1 when some did not (the summary says which); bad input throws.
// A negative tolerance selects the default (mappingTolerance: the meshes' chord gaps, as the adapter).
int mapCheckCommand(const std::string& src, const std::string& dst, double tolerance, const fs::path& jsonOut,
                    const MapCheckArgs& args, const std::vector<std::string>& sets) {
  // No run to stop cleanly here: Ctrl-C or SIGTERM ends the program as usual (and one sent during start-up
  // does).
  restoreDefaultInterrupts();
  if (!sets.empty() && !fsi::coupling::isSceneFile(src) && !fsi::coupling::isSceneFile(dst))
    throw fsi::InputError("--set applies to a structure scene (SCENE.yaml), but neither side is one");
  fsi::coupling::MapCheckOptions opt;
  opt.projection = mapCheckProjection(args);
  std::ofstream out;
  if (!jsonOut.empty()) {  // opened first so that a bad path fails before the work
    out.open(jsonOut);
    if (!out) throw fsi::InputError(fmt::format("{}: cannot write", jsonOut.string()));
  }
  const fsi::coupling::InterfaceMesh a = fsi::coupling::readInterfaceOrScene(src, sets);
  const fsi::coupling::InterfaceMesh b = fsi::coupling::readInterfaceOrScene(dst, sets);
  opt.tolerance = tolerance;
  const fsi::coupling::MapCheckResult r = fsi::coupling::runMapCheck(a, b, opt);
  fmt::print("{}", r.summary());
  if (!jsonOut.empty()) {
    out << r.toJson().dump(2) << "\n";
    if (!out) throw fsi::InputError(fmt::format("{}: write failed", jsonOut.string()));
  }
  return r.allMapped() ? 0 : 1;
}

// The plots are drawn by a Python script (matplotlib) installed next to the program: <exe dir>/../share/fsi
// (build/share/fsi in the build tree, PREFIX/share/fsi when installed). It replaces this process (execv, the
// arguments as a vector, no shell), so its exit code is ours: 0 written, 2 bad input, 1 modules missing.
int plotCommand(const fs::path& runDir, const fs::path& out, const std::string& color) {
  restoreDefaultInterrupts();  // no run to stop cleanly: signals end the program (and the script) as usual
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw std::runtime_error("cannot locate the fsi executable (/proc/self/exe): " + ec.message());
  const fs::path script = exe.parent_path().parent_path() / "share" / "fsi" / "fsi_plot.py";
  if (!fs::is_regular_file(script))
    throw std::runtime_error(
        fmt::format("{} not found: the fsi installation is incomplete (the build copies "
                    "apps/fsi/fsi_plot.py there)",
                    script.string()));
  const std::string python = "/usr/bin/python3";  // Debian's, with numpy, matplotlib and h5py
  if (::access(python.c_str(), X_OK) != 0)
    throw std::runtime_error(python + " not found: install python3-matplotlib python3-h5py");
  std::vector<std::string> args{python, script.string(), runDir.string(), "--color", color};
  if (!out.empty()) {
    args.emplace_back("--out");
    args.push_back(out.string());
  }
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  std::fflush(stderr);
  ::execv(python.c_str(), argv.data());
  throw std::runtime_error(fmt::format("cannot run {}: {}", python, std::strerror(errno)));
}

// A flight of the rigid parafoil-payload system (flight/, docs/FLIGHT.md): trajectory.csv and summary.json in
// OUT; `fsi plot OUT` draws it.
int flyCommand(const fs::path& file, const fs::path& outDir, const std::vector<std::string>& sets,
               bool quiet) {
  restoreDefaultInterrupts();  // seconds long: signals end the program as usual
  const fsi::flight::FlightCase c = fsi::flight::readFlightFile(file, sets);
  const fsi::flight::FlightResult r = fsi::flight::runFlight(c, outDir, quiet);
  fmt::print(
      "{}: {} after {:.1f} s at north {:.1f} m, east {:.1f} m{}; glide ratio over the last fifth {:.2f}, "
      "airspeed {:.2f} m/s, descent {:.2f} m/s\n{}/trajectory.csv, summary.json, summary.md{} (plots: fsi "
      "plot {})\n",
      file.string(), r.landed ? "landed" : "ended", r.time, r.landing.x(), r.landing.y(),
      r.landed ? "" : fmt::format(", altitude {:.1f} m", -r.landing.z()), r.glideRatio, r.airspeed,
      r.descentRate, outDir.string(), c.monteCarlo.enabled() ? ", monte_carlo.csv" : "", outDir.string());
  return 0;
}

}  // namespace

// `fsi scene-keys`: the declared scene schema (structure/scene/SceneSchema), as a list, as the markdown of
// docs/SCENES.md's key reference, or checked against a file's.
int sceneKeysCommand(bool markdown, const fs::path& checkDocs) {
  if (!checkDocs.empty()) {
    std::ifstream is(checkDocs);
    if (!is) throw fsi::InputError(fmt::format("{}: cannot open", checkDocs.string()));
    std::stringstream ss;
    ss << is.rdbuf();
    const std::vector<std::string> problems = schemaDocsProblems(ss.str());
    for (const std::string& p : problems) fmt::print(stderr, "{}: {}\n", checkDocs.string(), p);
    if (problems.empty())
      fmt::print("{}: the key reference agrees with the scene schema\n", checkDocs.string());
    return problems.empty() ? 0 : 1;
  }
  if (markdown) {
    fmt::print("{}", schemaMarkdown());
    return 0;
  }
  for (const SchemaSection* sec : sceneSchema()) {
    fmt::print("{}: {}\n", sec->path, sec->description);
    for (const SceneKey& k : sec->keys)
      fmt::print("  {:<20} {:<10} default {:<12} {:<24} {:<6} {}\n", k.name, toString(k.type),
                 k.defaultText(), k.rangeText(), k.unit, k.description);
  }
  return 0;
}

int main(int argc, char** argv) {
  // The effects that live in the coupling library (pressure_field): every scene this program loads has them.
  fsi::coupling::registerCouplingEffects();
  CLI::App app{"fsi: explicit membrane/cable structures and their coupling to flow solvers"};
  app.require_subcommand(1);

  auto* run = app.add_subcommand("run", "run a scene and write results, probes and statistics");
  fs::path scenePath, outDir;
  std::vector<std::string> sets;
  bool quiet = false;
  run->add_option("scene", scenePath, "scene YAML file")->required();
  run->add_option("--out,-o", outDir, "output directory")->required();
  run->add_option("--set", sets, "override a scene value: key.path=value (repeatable)");
  run->add_flag("--quiet,-q", quiet, "no progress output");
  fs::path startFrom;
  run->add_option("--start-from", startFrom,
                  "start a dynamic relaxation at another run's last frame (RUN or RUN/results.h5), "
                  "interpolated onto this mesh (e.g. a coarser run of the same geometry); or continue from "
                  "a state file of a run of this scene (RUN/interrupted_state.h5, RUN/last_good_state.h5)");

  auto* validate = app.add_subcommand("validate", "run a case's reference checks (CASE/reference.yaml)");
  fs::path caseDir, valOut;
  validate->add_option("case", caseDir, "case directory")->required();
  validate->add_option("--out,-o", valOut, "output directory (default results/validate/<case>)");
  validate->add_flag("--quiet,-q", quiet, "no progress output");

  auto* mapCheck = app.add_subcommand(
      "map-check", "check the projections between two interface meshes (FILE.msh[:GROUP] or CASE_DIR:PATCH)");
  std::string mapSrc, mapDst;
  double mapTolerance = -1.0;
  fs::path mapJson;
  const fsi::coupling::ProjectionOptions mapDefaults = fsi::coupling::coupledRunProjection();
  MapCheckArgs mapArgs{fsi::coupling::toString(mapDefaults.mass),
                       mapDefaults.quadratureLevel == fsi::coupling::kAutoQuadrature
                           ? std::string("auto")
                           : std::to_string(mapDefaults.quadratureLevel),
                       fsi::coupling::toString(mapDefaults.evaluation),
                       mapDefaults.gapCorrection ? "yes" : "no",
                       fsi::coupling::toString(mapDefaults.defectCorrection),
                       mapDefaults.keepSide ? "yes" : "no"};
  std::vector<std::string> mapSets;
  mapCheck
      ->add_option(
          "source", mapSrc,
          "first mesh (the structure): FILE.msh, FILE.msh:GROUP, CASE_DIR:PATCH or SCENE.yaml (its coupling "
          "interface)")
      ->required();
  mapCheck->add_option("target", mapDst, "second mesh (the fluid), same forms")->required();
  auto* mapTolOpt = mapCheck->add_option(
      "--tolerance,-t", mapTolerance,
      "absolute distance beyond which a point is unmapped (default, as a coupled run: max(0.25 x the "
      "source's mean edge, 2 x the two meshes' chord gaps))");
  mapCheck->add_option("--json", mapJson, "also write the results to this JSON file");
  // Every default below is the coupled run's (coupledRunProjection()): the check measures what the run gets.
  mapCheck->add_option("--variant", mapArgs.variant,
                       "L2 projection: consistent, lumped, dual or auto (consistent up to 5000 target nodes, "
                       "dual above); default " +
                           mapArgs.variant);
  mapCheck->add_option("--evaluation", mapArgs.evaluation,
                       "consistent transfer: pointwise (nearest projection) or l2 (the L2 projection); "
                       "default " +
                           mapArgs.evaluation);
  mapCheck->add_option("--quadrature-level", mapArgs.level,
                       "split each target triangle into level^2 for quadrature: auto (from the meshes' "
                       "edge-length ratio) or 1..64; default " +
                           mapArgs.level);
  mapCheck->add_option("--gap-correction", mapArgs.gapCorrection,
                       "yes|no: carry fields across the gap of curved meshes (docs/PROJECTION.md); default " +
                           mapArgs.gapCorrection);
  mapCheck->add_option("--keep-side", mapArgs.keepSide,
                       "yes|no: map points of a body wetted from one side onto the source facing their way "
                       "(thin edges; docs/PROJECTION.md); default " +
                           mapArgs.keepSide);
  mapCheck->add_option("--defect-correction", mapArgs.defect,
                       "auto (on when the target is 1.5x coarser than the source), on or off "
                       "(docs/PROJECTION.md); default " +
                           mapArgs.defect);
  mapCheck->add_option("--set", mapSets,
                       "override a value of the scene side(s): key.path=value (repeatable)");

  auto* plot =
      app.add_subcommand("plot", "PNG plots of a structure run (fsi run --out DIR) or a coupled case");
  fs::path plotDir, plotOut;
  std::string plotColor = "auto";
  plot->add_option("run", plotDir, "output folder of `fsi run`, or a coupled OpenFOAM case folder")
      ->required();
  plot->add_option("--out,-o", plotOut, "folder for the PNGs and index.json (default RUN/plots)");
  plot->add_option("--color", plotColor,
                   "structure picture coloured by: auto (major principal stress if written), stress or "
                   "displacement")
      ->check(CLI::IsMember({"auto", "stress", "displacement"}));

  auto* generate = app.add_subcommand(
      "generate", "write the meshes a scene builds (MESH.msh with its sets, MESH.stl of its outer surface)");
  fs::path genScene, genOut;
  std::vector<std::string> genSets;
  generate->add_option("scene", genScene, "scene YAML file")->required();
  generate->add_option("--out,-o", genOut, "output directory")->required();
  generate->add_option("--set", genSets, "override a scene value: key.path=value (repeatable)");
  fs::path genDeformed;
  generate->add_option(
      "--deformed", genDeformed,
      "the meshes at a run's last frame (RUN or RUN/results.h5: interpolated onto this scene's "
      "mesh, which may sample the same geometry finer; or a state file of a run of this scene)");

  auto* fly = app.add_subcommand(
      "fly", "fly the parafoil-payload system on a coefficient table (FLIGHT.yaml; docs/FLIGHT.md)");
  fs::path flyFile, flyOut;
  std::vector<std::string> flySets;
  bool flyQuiet = false;
  fly->add_option("flight", flyFile, "flight YAML file")->required();
  fly->add_option("--out,-o", flyOut, "output directory")->required();
  fly->add_option("--set", flySets, "override a value: key.path=value (repeatable)");
  fly->add_flag("--quiet,-q", flyQuiet, "no progress output");
  auto* sceneKeys = app.add_subcommand(
      "scene-keys",
      "print the declared scene schema: every key with type, default, range, unit, description");
  bool keysMarkdown = false;
  fs::path keysCheck;
  sceneKeys->add_flag("--markdown", keysMarkdown, "as the key reference of docs/SCENES.md (its tables)");
  sceneKeys->add_option(
      "--check-docs", keysCheck,
      "compare FILE's key reference (docs/SCENES.md) with the schema; exit 1 if they differ");

  // Exit codes (README): 0 done, 1 any other failure, 2 bad input (arguments included), 3 unstable, 4 not
  // converged, 130 interrupted by SIGINT, 143 by SIGTERM. CLI11's own codes (104-114) would be mistaken for
  // run results.
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help prints the usage and succeeds
    if (app.get_subcommands().empty() && argc > 1 && argv[1][0] != '-') {
      // CLI11 would only say "A subcommand is required"; name the word it did not know instead.
      std::string names;
      for (const CLI::App* c : app.get_subcommands([](CLI::App*) { return true; }))
        names += (names.empty() ? "" : ", ") + c->get_name();
      fmt::print(stderr, "error: unknown command '{}'; commands: {}\nrun 'fsi --help' for the usage\n",
                 argv[1], names);
      return 2;
    }
    fmt::print(stderr, "error: {}\nrun '{} --help' for the usage\n", e.what(),
               app.get_subcommands().empty() ? "fsi" : "fsi " + app.get_subcommands().front()->get_name());
    return 2;
  }
  try {
    if (*run) return runCommand(scenePath, outDir, sets, startFrom, quiet);
    if (*validate) return validateCommand(caseDir, valOut, quiet);
    if (*mapCheck) {
      if (mapTolOpt->count() > 0 && !(mapTolerance >= 0.0 && std::isfinite(mapTolerance)))
        throw fsi::InputError(fmt::format("--tolerance {}: must be a finite distance >= 0", mapTolerance));
      return mapCheckCommand(mapSrc, mapDst, mapTolOpt->count() > 0 ? mapTolerance : -1.0, mapJson, mapArgs,
                             mapSets);
    }
    if (*plot) return plotCommand(plotDir, plotOut, plotColor);
    if (*generate) {
      restoreDefaultInterrupts();  // no run to stop cleanly: signals end the program as usual
      return fsi::app::generateCommand(genScene, genOut, genSets, genDeformed);
    }
    if (*fly) return flyCommand(flyFile, flyOut, flySets, flyQuiet);
    if (*sceneKeys) return sceneKeysCommand(keysMarkdown, keysCheck);
  } catch (const fsi::InputError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  } catch (...) {
    fmt::print(stderr, "error: unknown failure\n");
    return 1;
  }
  return 0;
}
