// Dynamic relaxation speed on the 25x25 square cushion (TL1, 2028 dof) of the reference thesis, where one
// iteration took about 25 ms on a 2.93 GHz core.
//   build/bin/fsi_bench --benchmark_filter=Relaxation
// items_per_second = DR iterations per second (the scene is reloaded outside the timed region).
#include <benchmark/benchmark.h>

#include <filesystem>

#include "structure/integrate/DynamicRelaxation.hpp"
#include "structure/scene/Scene.hpp"

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

}  // namespace

BENCHMARK(BM_RelaxationCushion25)->Unit(benchmark::kMillisecond);
