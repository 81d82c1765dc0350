// Google Benchmark of the structure solver's hot loops.
//   build/bin/fsi_bench --benchmark_filter=Membrane      force kernel alone, 10^3..10^6 triangles (batched
//                                                        and the per-element reference)
//   build/bin/fsi_bench --benchmark_filter=Cable         cable force kernel alone, 10^3..10^6 cables (a
//                                                        stretched cable net; batched, the per-cable
//                                                        reference, viscous, 1 and 2 threads)
//   build/bin/fsi_bench --benchmark_filter=Step          full central-difference step
// items_per_second = element updates per second (triangles or cables).
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <cmath>
#include <map>
#include <memory>

#include "structure/effects/ThreadedForces.hpp"
#include "structure/elements/BuildModel.hpp"
#include "structure/elements/CableForces.hpp"
#include "structure/elements/MembraneForces.hpp"
#include "structure/integrate/CentralDifference.hpp"
#include "structure/scene/Scene.hpp"

using namespace fsi::structure;

namespace {

// A square sheet of about `triangles` cross-pattern triangles, pre-stretched and rippled so that the
// kernel sees a realistic mix of taut, wrinkled and slack elements (and their branches).
std::string sheetScene(long triangles, const std::string& extraEffects) {
  const int n = std::max(1, int(std::lround(std::sqrt(double(triangles) / 4.0))));
  return fmt::format(R"(materials:
  film: {{type: membrane, young: 1.0e9, poisson: 0.3, thickness: 1.0e-3, density: 1000}}
meshes:
  sheet:
    generator: {{type: rectangle, size: [1, 1], divisions: [{0}, {0}], pattern: cross}}
    material: film
constraints:
  - {{nodes: sheet/boundary, fix: all}}
effects:
  pressure: {{triangles: sheet, value: 100}}
  mass_damping: {{alpha: 10}}
{1}
time: {{end: 1.0}}
output: {{interval: 0}}
)",
                     n, extraEffects);
}

void deform(Model& m) {
  for (int i = 0; i < m.nodes.count; ++i) {
    const double X = m.nodes.X[3 * i], Y = m.nodes.X[3 * i + 1];
    m.nodes.x[3 * i] = X * 1.002 + 1e-3 * std::sin(40 * Y);
    m.nodes.x[3 * i + 1] = Y * (1.0 - 1e-3 * std::cos(7 * X));
    m.nodes.x[3 * i + 2] = 1e-3 * std::sin(30 * X) * std::sin(20 * Y);
  }
}

// Scenes are cached: building a 10^6-element model takes longer than measuring it.
Scene& cachedScene(long n, const std::string& extra) {
  static std::map<std::pair<long, std::string>, std::unique_ptr<Scene>> cache;
  auto& s = cache[{n, extra}];
  if (!s) {
    s = std::make_unique<Scene>(loadSceneFromString(sheetScene(n, extra), "bench.yaml"));
    deform(*s->model);
  }
  return *s;
}

// One effect's addForces on the model's current state, timed (forces accumulate: the arrays are not cleared).
void timeForceEffect(benchmark::State& state, Model& m, const Effect& effect, long items, const char* what) {
  ForceContext ctx;
  ctx.x = m.nodes.x.data();
  ctx.v = m.nodes.v.data();
  ctx.fint = m.nodes.fint.data();
  ctx.fext = m.nodes.fext.data();
  for (auto _ : state) {
    ctx.minStableDt = 1e300;
    effect.addForces(ctx);
    benchmark::DoNotOptimize(ctx.minStableDt);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * items);
  state.counters[what] = static_cast<double>(items);
}

// The scene's membrane effect (batched kernel), or the per-element reference kernel on the same model.
void membraneKernel(benchmark::State& state, MembraneKernel kernel) {
  Scene& s = cachedScene(state.range(0), "");
  Model& m = *s.model;
  const MembraneForces perElement(m.membranes, {}, MembraneKernel::PerElement);
  // The element forces come first in the scene's list; this sheet has no cables.
  const Effect* membrane = kernel == MembraneKernel::Batched ? s.effectList().front() : &perElement;
  timeForceEffect(state, m, *membrane, m.membranes.count, "triangles");
}

void BM_MembraneKernel(benchmark::State& state) {
  membraneKernel(state, MembraneKernel::Batched);
}
void BM_MembraneKernelPerElement(benchmark::State& state) {
  membraneKernel(state, MembraneKernel::PerElement);
}
// One effect through the solver's threaded evaluation (ThreadedForces, solver.threads: N), timed: with the
// clearing of the force arrays, so the 1-thread variant (the serial evaluateEffects) is the reference for
// the N-thread one. Register with UseRealTime(): the CPU time counts the calling thread only.
void timeThreadedEffect(benchmark::State& state, Model& m, const Effect& effect, int threads, long items,
                        const char* what) {
  ThreadedForces forces({&effect}, threads, m.nodes.count);
  for (auto _ : state) {
    const ForceContext ctx = forces.evaluate(m.nodes, 0.0, 1.0, false);
    benchmark::DoNotOptimize(ctx.minStableDt);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * items);
  state.counters[what] = static_cast<double>(items);
  state.counters["shares"] = forces.shares();
}

// The batched membrane kernel on N threads.
void membraneKernelThreads(benchmark::State& state, int threads) {
  Scene& s = cachedScene(state.range(0), "");
  Model& m = *s.model;
  timeThreadedEffect(state, m, *s.effectList().front(), threads, m.membranes.count, "triangles");
}
void BM_MembraneKernelThreads1(benchmark::State& state) {
  membraneKernelThreads(state, 1);
}
void BM_MembraneKernelThreads2(benchmark::State& state) {
  membraneKernelThreads(state, 2);
}

// The fabric's bending alone through ThreadedForces (hinge angles, barrier, hinge moments; clearing
// included; wall time), 1 and 2 threads; items are triangles (≈ 1.5 hinges each).
const char* kBending = "  bending: {triangles: sheet, rigidity: 1.0e-3}";
void bendingThreads(benchmark::State& state, int threads) {
  Scene& s = cachedScene(state.range(0), kBending);
  Model& m = *s.model;
  const Effect* bending = nullptr;
  for (const Effect* e : s.effectList())
    if (e->name().rfind("bending", 0) == 0) bending = e;
  timeThreadedEffect(state, m, *bending, threads, m.membranes.count, "triangles");
  state.counters["hinges"] = bending->connectivity().items;
}
void BM_BendingThreads1(benchmark::State& state) {
  bendingThreads(state, 1);
}
void BM_BendingThreads2(benchmark::State& state) {
  bendingThreads(state, 2);
}

// The pressure effect alone (the scene's only load).
void BM_PressureKernel(benchmark::State& state) {
  Scene& s = cachedScene(state.range(0), "");
  Model& m = *s.model;
  const Effect* pressure = s.effectList().back();
  ForceContext ctx;
  ctx.x = m.nodes.x.data();
  ctx.fint = m.nodes.fint.data();
  ctx.fext = m.nodes.fext.data();
  for (auto _ : state) {
    pressure->addForces(ctx);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * m.membranes.count);
}

// A square net of about `cables` cables: an n x n grid of nodes 1 m wide with a cable along every grid
// line segment (2 n (n - 1) cables, sorted like any model's), stretched by 0.3 % with ripples, so that about
// 10 % of the cables are slack and the rest taut at strains up to 0.7 %; velocities for the viscous variant.
struct CableNet {
  Model model;
  std::unique_ptr<CableForces> elastic, viscous, perElement, perElementViscous;
};
CableNet& cachedNet(long cables) {
  static std::map<long, std::unique_ptr<CableNet>> cache;
  auto& net = cache[cables];
  if (net) return *net;
  const int n = std::max(2, int(std::lround(0.5 + std::sqrt(0.25 + double(cables) / 2.0))));
  MeshInput in;
  in.mesh.name = "net";
  auto node = [n](int i, int j) { return j * n + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      in.mesh.points.push_back({double(i) / (n - 1), double(j) / (n - 1), 0.0});
      in.mesh.pointTags.push_back(long(in.mesh.points.size()));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (i + 1 < n) in.mesh.lines.push_back({node(i, j), node(i + 1, j)});
      if (j + 1 < n) in.mesh.lines.push_back({node(i, j), node(i, j + 1)});
    }
  in.cableMaterial = 0;
  // A 4 mm aramid line: E = 70 GPa, A = 12.6 mm², 1440 kg/m³.
  net = std::make_unique<CableNet>(
      CableNet{buildModel({in}, {}, {CableMaterial{"line", 7.0e10, 1.26e-5, 1440}}), nullptr, nullptr,
               nullptr, nullptr});
  Nodes& N = net->model.nodes;
  for (int i = 0; i < N.count; ++i) {
    const double X = N.X[3 * i], Y = N.X[3 * i + 1];
    N.x[3 * i] = 1.003 * X + 8e-5 * std::sin(50 * X) + 1e-4 * std::sin(40 * Y);
    N.x[3 * i + 1] = 1.003 * Y + 6e-5 * std::sin(50 * Y);
    N.x[3 * i + 2] = 1e-3 * std::sin(30 * X) * std::sin(20 * Y);
    for (int k = 0; k < 3; ++k) N.v[3 * i + k] = 0.1 * std::sin(13.0 * i + 5.0 * k);
  }
  net->elastic = std::make_unique<CableForces>(net->model.cables, CableViscosity{});
  net->viscous = std::make_unique<CableForces>(net->model.cables, CableViscosity{1.0e-7, 0.06});
  net->perElement =
      std::make_unique<CableForces>(net->model.cables, CableViscosity{}, CableKernel::PerElement);
  net->perElementViscous =
      std::make_unique<CableForces>(net->model.cables, CableViscosity{1.0e-7, 0.06}, CableKernel::PerElement);
  return *net;
}

// The cable effect's addForces on the net, batched kernel or the per-cable reference (forces accumulate; the
// arrays are not cleared, as in BM_MembraneKernel).
void cableKernel(benchmark::State& state, bool viscous, CableKernel kernel = CableKernel::Batched) {
  CableNet& net = cachedNet(state.range(0));
  Model& m = net.model;
  const Effect* cable = kernel == CableKernel::Batched
                            ? (viscous ? net.viscous.get() : net.elastic.get())
                            : (viscous ? net.perElementViscous.get() : net.perElement.get());
  timeForceEffect(state, m, *cable, m.cables.count, "cables");
}
void BM_CableKernel(benchmark::State& state) {
  cableKernel(state, false);
}
void BM_CableKernelViscous(benchmark::State& state) {
  cableKernel(state, true);
}
void BM_CableKernelPerElement(benchmark::State& state) {
  cableKernel(state, false, CableKernel::PerElement);
}
void BM_CableKernelViscousPerElement(benchmark::State& state) {
  cableKernel(state, true, CableKernel::PerElement);
}
// The cable effect through ThreadedForces (clearing of the force arrays included; wall time), 1 and 2
// threads, like BM_MembraneKernelThreads1/2.
void cableKernelThreads(benchmark::State& state, int threads) {
  CableNet& net = cachedNet(state.range(0));
  Model& m = net.model;
  timeThreadedEffect(state, m, *net.elastic, threads, m.cables.count, "cables");
}
void BM_CableKernelThreads1(benchmark::State& state) {
  cableKernelThreads(state, 1);
}
void BM_CableKernelThreads2(benchmark::State& state) {
  cableKernelThreads(state, 2);
}

// The integrator's node sweep with no effect at all (fixed step): what a step costs besides the effects.
void BM_NodeSweep(benchmark::State& state) {
  Scene& s = cachedScene(state.range(0), "");
  Model& m = *s.model;
  CentralDifferenceSettings settings = s.time.integrator;
  settings.fixedDt = 1e-9;
  CentralDifference cd(m, {}, s.constraints, settings);
  for (auto _ : state) {
    cd.step(1e300, false);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * m.membranes.count);
}

void runSteps(benchmark::State& state, const std::string& extra,
              MembraneKernel kernel = MembraneKernel::Batched, int threads = 1) {
  Scene& s = cachedScene(state.range(0), extra);
  Model& m = *s.model;
  std::vector<const Effect*> effects = s.effectList();
  const MembraneForces perElement(m.membranes, {}, MembraneKernel::PerElement);
  if (kernel == MembraneKernel::PerElement) effects.front() = &perElement;  // the scenes have no viscosity
  CentralDifferenceSettings settings = s.time.integrator;
  settings.threads = threads;
  CentralDifference cd(m, effects, s.constraints, settings);
  for (auto _ : state) {
    cd.step(1e300, false);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * (m.membranes.count + m.cables.count));
  state.counters["triangles"] = m.membranes.count;
}

void BM_Step(benchmark::State& state) {
  runSteps(state, "");
}
void BM_StepPerElement(benchmark::State& state) {
  runSteps(state, "", MembraneKernel::PerElement);
}
void BM_StepThreads2(benchmark::State& state) {
  runSteps(state, "", MembraneKernel::Batched, 2);
}
// A step with the fabric's bending (membranes, pressure, bending), 1 and 2 threads (wall time).
void BM_StepWithBendingThreads1(benchmark::State& state) {
  runSteps(state, kBending, MembraneKernel::Batched, 1);
}
void BM_StepWithBendingThreads2(benchmark::State& state) {
  runSteps(state, kBending, MembraneKernel::Batched, 2);
}
void BM_StepWithViscosityAndGravity(benchmark::State& state) {
  runSteps(state,
           "  stiffness_damping: {beta: 1.0e-7}\n  bulk_viscosity: {b1: 0.06}\n  gravity: {acceleration: [0, "
           "0, -9.81]}");
}

}  // namespace

BENCHMARK(BM_MembraneKernel)->RangeMultiplier(10)->Range(1000, 1000000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MembraneKernelPerElement)
    ->RangeMultiplier(10)
    ->Range(1000, 1000000)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CableKernel)->RangeMultiplier(10)->Range(1000, 1000000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CableKernelPerElement)->RangeMultiplier(10)->Range(1000, 1000000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CableKernelViscous)->RangeMultiplier(10)->Range(1000, 1000000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CableKernelViscousPerElement)
    ->RangeMultiplier(10)
    ->Range(1000, 1000000)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CableKernelThreads1)
    ->RangeMultiplier(10)
    ->Range(1000, 1000000)
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK(BM_CableKernelThreads2)
    ->RangeMultiplier(10)
    ->Range(1000, 1000000)
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK(BM_PressureKernel)->RangeMultiplier(10)->Range(1000, 1000000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_NodeSweep)->RangeMultiplier(10)->Range(1000, 1000000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Step)->RangeMultiplier(10)->Range(1000, 1000000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StepPerElement)->RangeMultiplier(10)->Range(1000, 1000000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MembraneKernelThreads1)
    ->RangeMultiplier(10)
    ->Range(1000, 1000000)
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK(BM_MembraneKernelThreads2)
    ->RangeMultiplier(10)
    ->Range(1000, 1000000)
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK(BM_StepThreads2)
    ->RangeMultiplier(10)
    ->Range(1000, 1000000)
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
// Between the decades, for the serial threshold (kMinParallelItems): wall time at 1 and 2 threads.
void BM_StepThreads1(benchmark::State& state) {
  runSteps(state, "", MembraneKernel::Batched, 1);
}
BENCHMARK(BM_StepThreads1)
    ->Arg(2000)
    ->Arg(5000)
    ->Arg(20000)
    ->Arg(50000)
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK(BM_StepThreads2)
    ->Arg(2000)
    ->Arg(5000)
    ->Arg(20000)
    ->Arg(50000)
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK(BM_BendingThreads1)->Arg(10000)->Arg(100000)->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK(BM_BendingThreads2)->Arg(10000)->Arg(100000)->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK(BM_StepWithBendingThreads1)->Arg(10000)->Arg(100000)->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK(BM_StepWithBendingThreads2)->Arg(10000)->Arg(100000)->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK(BM_StepWithViscosityAndGravity)->Arg(10000)->Arg(100000)->Unit(benchmark::kMicrosecond);
