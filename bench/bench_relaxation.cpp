// Dynamic relaxation speed.
//   build/bin/fsi_bench --benchmark_filter=Relaxation
//
// BM_RelaxationCushion25: the whole solve of the 25x25 square cushion (TL1, 2028 dof) of the reference
// thesis, where one iteration took about 25 ms on a 2.93 GHz core; items_per_second = DR iterations per
// second (the scene is reloaded outside the timed region).
//
// BM_RelaxationIteration/triangles:T/threads:P: wall time per iteration of the pressurised film with cables
// of tests/unit/CabledSheet.hpp (4 n² triangles, 6 n cables) on P threads (solver.threads): the first K
// iterations from the flat start less a run that stops before its first iteration (fictitious masses, first
// evaluation), i.e. one iteration (force evaluation and node loops, kinetic resets included),
// K = 4·10⁶ / triangles; two such runs per repetition (about 0.2 s each on one core). Counter cpu_us: the
// calling thread's CPU time per iteration. docs/PERFORMANCE.md "Threaded dynamic relaxation".
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <map>
#include <memory>

#include "structure/integrate/DynamicRelaxation.hpp"
#include "structure/scene/Scene.hpp"
#include "tests/unit/CabledSheet.hpp"

using namespace fsi::structure;

namespace {

void BM_RelaxationCushion25(benchmark::State& state) {
  const std::filesystem::path scene =
      std::filesystem::path(FSI_SOURCE_DIR) / "cases/structure/cushion-square-25/scene.yaml";
  long iterations = 0;
  for (auto _ : state) {
    state.PauseTiming();
    Scene s = loadScene(scene);
    DynamicRelaxation dr(*s.model, s.effectList(), s.constraints, s.solver.relaxation);
    state.ResumeTiming();
    const RelaxationResult r = dr.run();
    iterations += r.iterations;
    if (r.reason != StopReason::Static) state.SkipWithError("did not converge");
  }
  state.SetItemsProcessed(iterations);
  state.counters["iterations_per_solve"] =
      benchmark::Counter(double(iterations) / double(state.iterations()), benchmark::Counter::kDefaults);
}

// The cabled sheet of about `triangles` triangles, loaded once per size.
Scene& cabledSheet(long triangles) {
  static std::map<long, std::unique_ptr<Scene>> cache;
  auto& s = cache[triangles];
  if (!s) {
    const int n = std::max(2, int(std::lround(std::sqrt(double(triangles) / 4.0))));
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("fsi_bench_cabled_sheet_" + std::to_string(n));
    const std::string yaml = fsi::test::writeCabledSheet(dir, n, "tolerance: 1.0e-12");
    s = std::make_unique<Scene>(loadSceneFromString(yaml, (dir / "sheet.yaml").string()));
  }
  return *s;
}

double threadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// Wall seconds of a relaxation of at most `iterations` iterations from the flat start; `done` gets its count,
// `cpu` the calling thread's CPU seconds.
double relax(Scene& s, int threads, long iterations, long& done, double& cpu) {
  Nodes& N = s.model->nodes;
  N.x = N.X;
  std::fill(N.v.begin(), N.v.end(), 0.0);
  RelaxationSettings rs = s.solver.relaxation;
  rs.threads = threads;
  rs.maxIterations = iterations;
  DynamicRelaxation dr(*s.model, s.effectList(), s.constraints, rs);
  const double c0 = threadCpuSeconds();
  const auto t0 = std::chrono::steady_clock::now();
  const RelaxationResult r = dr.run();
  const auto t1 = std::chrono::steady_clock::now();
  cpu = threadCpuSeconds() - c0;
  done = r.iterations;
  return std::chrono::duration<double>(t1 - t0).count();
}

void BM_RelaxationIteration(benchmark::State& state) {
  Scene& s = cabledSheet(state.range(0));
  const int threads = int(state.range(1));
  const long k = std::max(10L, 4000000L / long(s.model->membranes.count));
  long done = 0, total = 0;
  double cpu = 0, cpuStart = 0, cpuAll = 0;
  for (auto _ : state) {
    const double start = relax(s, threads, 0, done, cpuStart);
    const double all = relax(s, threads, k, done, cpuAll);
    total += done;
    cpu += (cpuAll - cpuStart) / double(done);
    state.SetIterationTime((all - start) / double(done));
  }
  // The calling thread's CPU time per iteration (µs): on a loaded machine it shows the split of the work
  // that the wall time hides.
  state.counters["cpu_us"] = 1e6 * cpu / double(state.iterations());
  state.counters["triangles"] = s.model->membranes.count;
  state.counters["cables"] = s.model->cables.count;
  state.counters["iterations_per_run"] = double(total) / double(state.iterations());
}

}  // namespace

BENCHMARK(BM_RelaxationCushion25)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RelaxationIteration)
    ->ArgNames({"triangles", "threads"})
    ->Args({10000, 1})
    ->Args({10000, 2})
    ->Args({100000, 1})
    ->Args({100000, 2})
    ->Iterations(2)
    ->Unit(benchmark::kMicrosecond)
    ->UseManualTime();
