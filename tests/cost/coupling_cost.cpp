// fsi_coupling_cost: one coupled run of the added-mass drum (tests/unit/AddedMassDrum.hpp: the real explicit
// membrane solver, a reduced fluid that is its added mass) with the given coupling knobs, or its monolithic
// reference; prints one JSON object. studies/cost/accuracy_cost.py runs it per setting for the coupled knobs.
//
//   fsi_coupling_cost [--scheme staggered|implicit] [--acceleration IQN-ILS|Aitken|constant] [--omega W]
//                     [--reuse Q] [--tolerance T] [--max-iterations N] [--subcycles N] [--window DT]
//                     [--end T] [--added-mass MA] [--out DIR]
//   fsi_coupling_cost --monolithic [--end T] [--added-mass MA] [--safety S] --out DIR
//
// Output: {"finite", "centre" [m], "windows", "mean_iterations", "structural_steps", "wall_seconds"}; the
// monolithic run: {"centre", "wall_seconds"}. Exit code 2 on a bad argument.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include "AddedMassDrum.hpp"
#include "coupling/scheme/acceleration/Aitken.hpp"
#include "coupling/scheme/acceleration/ConstantRelaxation.hpp"
#include "coupling/scheme/acceleration/IqnIls.hpp"

namespace {

[[noreturn]] void usage(const std::string& message) {
  std::fprintf(stderr, "fsi_coupling_cost: %s\n", message.c_str());
  std::exit(2);
}

double number(const std::string& option, const char* text) {
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(v)) usage(option + " " + text + ": not a number");
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace fsi;
  test::DrumSettings c;
  std::string acceleration = "IQN-ILS",
              out = (std::filesystem::temp_directory_path() / "fsi_coupling_cost").string();
  double omega = -1.0, end = 0.08, safety = 0.9;
  int reuse = 0;
  bool monolithic = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--monolithic") {
      monolithic = true;
      continue;
    }
    if (i + 1 >= argc) usage(a + ": missing value");
    const char* v = argv[++i];
    if (a == "--scheme") {
      const std::string s = v;
      if (s != "staggered" && s != "implicit") usage("--scheme " + s + ": must be staggered or implicit");
      c.kind = s == "staggered" ? coupling::SchemeKind::Staggered : coupling::SchemeKind::Implicit;
    } else if (a == "--acceleration") {
      acceleration = v;
      if (acceleration != "IQN-ILS" && acceleration != "Aitken" && acceleration != "constant")
        usage("--acceleration " + acceleration + ": must be IQN-ILS, Aitken or constant");
    } else if (a == "--omega") {
      omega = number(a, v);
    } else if (a == "--reuse") {
      reuse = int(number(a, v));
    } else if (a == "--tolerance") {
      c.relativeTolerance = number(a, v);
    } else if (a == "--max-iterations") {
      c.maxIterations = int(number(a, v));
    } else if (a == "--subcycles") {
      c.minSubcycles = int(number(a, v));
    } else if (a == "--window") {
      c.window = number(a, v);
    } else if (a == "--end") {
      end = number(a, v);
    } else if (a == "--added-mass") {
      c.addedMass = number(a, v);
    } else if (a == "--safety") {
      safety = number(a, v);
    } else if (a == "--out") {
      out = v;
    } else {
      usage("unknown option " + a);
    }
  }
  if (monolithic) {
    const auto t0 = std::chrono::steady_clock::now();
    const double w = test::addedMassDrumMonolithic(c.addedMass, end, out, safety);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("{\"centre\": %.17g, \"wall_seconds\": %.6g}\n", w, wall);
    return 0;
  }
  c.windows = int(std::lround(end / c.window));
  std::unique_ptr<coupling::Acceleration> acc;
  if (c.kind == coupling::SchemeKind::Implicit) {
    if (acceleration == "IQN-ILS") {
      coupling::IqnIlsOptions o;
      if (omega > 0) o.initialOmega = omega;
      o.reuseSteps = reuse;
      acc = std::make_unique<coupling::IqnIls>(o);
    } else if (acceleration == "Aitken") {
      coupling::AitkenOptions o;
      if (omega > 0) o.initialOmega = omega;
      acc = std::make_unique<coupling::Aitken>(o);
    } else {
      acc = std::make_unique<coupling::ConstantRelaxation>(omega > 0 ? omega : 0.1);
    }
  }
  const test::DrumRun r = test::runAddedMassDrum(c, std::move(acc));
  std::printf(
      "{\"finite\": %s, \"centre\": %.17g, \"windows\": %d, \"mean_iterations\": %.6g, \"structural_steps\": "
      "%ld, "
      "\"wall_seconds\": %.6g}\n",
      r.finite ? "true" : "false", r.finite ? r.centre : 0.0, r.windows, r.meanIterations, r.structuralSteps,
      r.wallSeconds);
  return 0;
}
