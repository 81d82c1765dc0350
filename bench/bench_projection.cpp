// Google Benchmark of the interface projection (coupling/mapping/L2Projection).
//   fsi_bench --benchmark_filter=Projection
// Meshes: a flat unit square, source = structured triangles (the structure), target = structured quads 1.3×
// finer (the fluid), so no node, edge or quadrature point of one lies on a mesh line of the other. The
// argument is the number of target nodes. items_per_second = target nodes per second (one field transfer).
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include "coupling/mapping/L2Projection.hpp"

using namespace fsi::coupling;

namespace {

InterfaceMesh squareMesh(int n, bool quads) {
  InterfaceMesh m;
  m.name = quads ? "quads" : "triangles";
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.points.push_back({double(i) / n, double(j) / n, 0.0});
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (quads) {
        m.addFace({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        m.addFace({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        m.addFace({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  return m;
}

struct Case {
  InterfaceMesh source, target;
};

Case makeCase(long targetNodes) {
  const int nt = std::max(2, int(std::lround(std::sqrt(double(targetNodes)))) - 1);
  const int ns = std::max(1, int(std::lround(nt / 1.3)));
  return {squareMesh(ns, false), squareMesh(nt, true)};
}

// Google Benchmark calls a benchmark function several times while it sizes the iteration count, and the
// apply benchmarks revisit every size: set each projection up once (10^6 nodes take seconds).
const L2Projection& cachedProjection(long targetNodes, MassMatrix mass) {
  static std::map<std::pair<long, MassMatrix>, std::unique_ptr<L2Projection>> cache;
  std::unique_ptr<L2Projection>& p = cache[{targetNodes, mass}];
  if (!p) {
    const Case c = makeCase(targetNodes);
    p = std::make_unique<L2Projection>(c.source, c.target, ProjectionOptions{mass, 1e-9, 1});
  }
  return *p;
}

void setup(benchmark::State& state, MassMatrix mass) {
  const Case c = makeCase(state.range(0));
  double search = 0, assembly = 0, factor = 0;
  for (auto _ : state) {
    const L2Projection h(c.source, c.target, ProjectionOptions{mass, 1e-9, 1});
    benchmark::DoNotOptimize(&h);
    search += h.report().searchSeconds;
    assembly += h.report().assemblySeconds;
    factor += h.report().factorSeconds;
  }
  const double n = double(state.iterations());
  state.counters["search_s"] = search / n;
  state.counters["assembly_s"] = assembly / n;
  state.counters["factor_s"] = factor / n;
  state.counters["target_nodes"] = c.target.numPoints();
  state.counters["source_nodes"] = c.source.numPoints();
  state.SetComplexityN(c.target.numPoints());
  state.SetItemsProcessed(long(state.iterations()) * c.target.numPoints());
}

void apply(benchmark::State& state, MassMatrix mass, int components, bool transpose) {
  const L2Projection& h = cachedProjection(state.range(0), mass);
  std::vector<double> us(std::size_t(components) * std::size_t(h.sourceSize()), 1.0),
      ut(std::size_t(components) * std::size_t(h.targetSize()), 1.0);
  for (auto _ : state) {
    if (transpose)
      h.applyTranspose(ut.data(), us.data(), components);
    else
      h.apply(us.data(), ut.data(), components);
    benchmark::ClobberMemory();
  }
  state.counters["target_nodes"] = h.targetSize();
  state.counters["nnz_C"] = double(h.coupling().nonZeros());
  state.SetComplexityN(h.targetSize());
  state.SetItemsProcessed(long(state.iterations()) * h.targetSize());
}

void BM_ProjectionSetupConsistent(benchmark::State& s) {
  setup(s, MassMatrix::Consistent);
}
void BM_ProjectionSetupLumped(benchmark::State& s) {
  setup(s, MassMatrix::Lumped);
}
void BM_ProjectionSetupDual(benchmark::State& s) {
  setup(s, MassMatrix::Dual);
}
void BM_ProjectionApplyConsistentScalar(benchmark::State& s) {
  apply(s, MassMatrix::Consistent, 1, false);
}
void BM_ProjectionApplyConsistentVector(benchmark::State& s) {
  apply(s, MassMatrix::Consistent, 3, false);
}
void BM_ProjectionTransposeConsistentVector(benchmark::State& s) {
  apply(s, MassMatrix::Consistent, 3, true);
}
void BM_ProjectionApplyLumpedScalar(benchmark::State& s) {
  apply(s, MassMatrix::Lumped, 1, false);
}
void BM_ProjectionApplyLumpedVector(benchmark::State& s) {
  apply(s, MassMatrix::Lumped, 3, false);
}
void BM_ProjectionTransposeLumpedVector(benchmark::State& s) {
  apply(s, MassMatrix::Lumped, 3, true);
}
void BM_ProjectionApplyDualScalar(benchmark::State& s) {
  apply(s, MassMatrix::Dual, 1, false);
}
void BM_ProjectionApplyDualVector(benchmark::State& s) {
  apply(s, MassMatrix::Dual, 3, false);
}
void BM_ProjectionTransposeDualVector(benchmark::State& s) {
  apply(s, MassMatrix::Dual, 3, true);
}

// MassMatrix::Auto: consistent up to kAutoConsistentMaxNodes target nodes, dual above.
void BM_ProjectionApplyAutoScalar(benchmark::State& s) {
  apply(s, MassMatrix::Auto, 1, false);
}
void BM_ProjectionApplyAutoVector(benchmark::State& s) {
  apply(s, MassMatrix::Auto, 3, false);
}
void BM_ProjectionTransposeAutoVector(benchmark::State& s) {
  apply(s, MassMatrix::Auto, 3, true);
}

// A curved non-matching interface, the case of issue 16: a unit sphere, cubed with n × n cells per cube
// face (6n² + 2 vertices), fine triangles (n = 32, 6146 nodes) projected onto coarse quads (n = 10, 602
// nodes, rotated), consistent, automatic quadrature level. Argument: 0 = plain projection (no gap, no
// defect correction), 1 = gap correction, 2 = gap and defect correction (the default here): the cost of
// the corrections (setup, nnz of C, apply).
InterfaceMesh cubedSphere(int n, bool triangles, double angle) {
  InterfaceMesh m;
  m.name = "sphere";
  const double pi = std::acos(-1.0), c = std::cos(angle), s = std::sin(angle);
  std::map<std::array<int, 3>, int> ids;
  auto vertex = [&](const std::array<int, 3>& l) {
    auto it = ids.find(l);
    if (it != ids.end()) return it->second;
    std::array<double, 3> p;
    for (int k = 0; k < 3; ++k) p[std::size_t(k)] = std::tan(pi / 4 * (2.0 * l[std::size_t(k)] / n - 1.0));
    const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    m.points.push_back({(c * p[0] - s * p[1]) / r, (s * p[0] + c * p[1]) / r, p[2] / r});  // about z
    ids.emplace(l, m.numPoints() - 1);
    return m.numPoints() - 1;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side)
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          std::array<int, 4> q;
          const int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
          for (int k = 0; k < 4; ++k) {
            std::array<int, 3> l{};
            l[std::size_t(axis)] = side * n;
            l[std::size_t((axis + 1) % 3)] = i + di[k];
            l[std::size_t((axis + 2) % 3)] = j + dj[k];
            q[std::size_t(k)] = vertex(l);
          }
          if (triangles) {
            m.addFace({q[0], q[1], q[2]});
            m.addFace({q[0], q[2], q[3]});
          } else {
            m.addFace({q[0], q[1], q[2], q[3]});
          }
        }
  return m;
}

const InterfaceMesh& fineSphere() {
  static const InterfaceMesh m = cubedSphere(32, true, 0.0);
  return m;
}
const InterfaceMesh& coarseSphere() {
  static const InterfaceMesh m = cubedSphere(10, false, 0.37);
  return m;
}

ProjectionOptions sphereOptions(long setup) {
  return {MassMatrix::Consistent, HUGE_VAL, kAutoQuadrature, setup >= 1,
          setup >= 2 ? ProjectionOptions::Defect::On : ProjectionOptions::Defect::Off};
}

void BM_ProjectionSphereSetup(benchmark::State& state) {
  const ProjectionOptions o = sphereOptions(state.range(0));
  long nnz = 0;
  for (auto _ : state) {
    const L2Projection h(fineSphere(), coarseSphere(), o);
    nnz = h.coupling().nonZeros();
    benchmark::DoNotOptimize(&h);
  }
  state.counters["nnz_C"] = double(nnz);
}
void BM_ProjectionSphereApplyScalar(benchmark::State& state) {
  static std::map<long, std::unique_ptr<L2Projection>> cache;
  std::unique_ptr<L2Projection>& h = cache[state.range(0)];
  if (!h) h = std::make_unique<L2Projection>(fineSphere(), coarseSphere(), sphereOptions(state.range(0)));
  std::vector<double> us(std::size_t(h->sourceSize()), 1.0), ut(std::size_t(h->targetSize()));
  for (auto _ : state) {
    h->apply(us.data(), ut.data());
    benchmark::ClobberMemory();
  }
  state.counters["nnz_C"] = double(h->coupling().nonZeros());
  state.SetItemsProcessed(long(state.iterations()) * h->targetSize());
}

// 10^3 .. max target nodes; setup is expected to grow as N log N, apply as N.
void setupSizes(benchmark::internal::Benchmark* b, long max) {
  b->RangeMultiplier(10)->Range(1000, max)->Unit(benchmark::kMillisecond)->Complexity(benchmark::oNLogN);
}
void applySizes(benchmark::internal::Benchmark* b, long max) {
  b->RangeMultiplier(10)->Range(1000, max)->Unit(benchmark::kMicrosecond)->Complexity(benchmark::oN);
}

}  // namespace

// Consistent stops at 10^5: its LDLᵀ factorisation of M_t takes minutes at 10^6 (see docs/PROJECTION.md).
BENCHMARK(BM_ProjectionSetupConsistent)->Apply([](auto* b) { setupSizes(b, 100000); });
BENCHMARK(BM_ProjectionSetupLumped)->Apply([](auto* b) { setupSizes(b, 1000000); });
BENCHMARK(BM_ProjectionSetupDual)->Apply([](auto* b) { setupSizes(b, 1000000); });
BENCHMARK(BM_ProjectionApplyConsistentScalar)->Apply([](auto* b) { applySizes(b, 100000); });
BENCHMARK(BM_ProjectionApplyConsistentVector)->Apply([](auto* b) { applySizes(b, 100000); });
BENCHMARK(BM_ProjectionTransposeConsistentVector)->Apply([](auto* b) { applySizes(b, 100000); });
BENCHMARK(BM_ProjectionApplyLumpedScalar)->Apply([](auto* b) { applySizes(b, 1000000); });
BENCHMARK(BM_ProjectionApplyLumpedVector)->Apply([](auto* b) { applySizes(b, 1000000); });
BENCHMARK(BM_ProjectionTransposeLumpedVector)->Apply([](auto* b) { applySizes(b, 1000000); });
BENCHMARK(BM_ProjectionApplyDualScalar)->Apply([](auto* b) { applySizes(b, 1000000); });
BENCHMARK(BM_ProjectionApplyDualVector)->Apply([](auto* b) { applySizes(b, 1000000); });
BENCHMARK(BM_ProjectionTransposeDualVector)->Apply([](auto* b) { applySizes(b, 1000000); });
BENCHMARK(BM_ProjectionApplyAutoScalar)->Apply([](auto* b) { applySizes(b, 1000000); });
BENCHMARK(BM_ProjectionApplyAutoVector)->Apply([](auto* b) { applySizes(b, 1000000); });
BENCHMARK(BM_ProjectionTransposeAutoVector)->Apply([](auto* b) { applySizes(b, 1000000); });
BENCHMARK(BM_ProjectionSphereSetup)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ProjectionSphereApplyScalar)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
