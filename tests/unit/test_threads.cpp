// Threads (scene key solver.threads): the threaded membrane kernel and node sweep give the serial results to
// round-off (only the order of the sums at the nodes and of the energy sums differs), and the key is checked
// like every other scene key.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "MembraneEvaluation.hpp"
#include "TestScenes.hpp"
#include "structure/effects/Threads.hpp"
#include "structure/elements/MembraneForces.hpp"
#include "structure/integrate/CentralDifference.hpp"
#include "structure/model/Error.hpp"
#include "structure/scene/Scene.hpp"

using namespace fsi::structure;

namespace {

// A clamped, pressurised sheet of 4 n² triangles (above kMinParallelItems), rippled into a mix of taut,
// wrinkled and slack triangles, with velocities for the viscous stresses.
Scene rippledSheet(int n, const std::string& extra = "") {
  Scene s = loadSceneFromString(fmt::format(R"(materials:
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
time: {{end: 1.0}}
{1}
)",
                                            n, extra),
                                "sheet.yaml");
  Model& m = *s.model;
  for (int i = 0; i < m.nodes.count; ++i) {
    const double X = m.nodes.X[3 * i], Y = m.nodes.X[3 * i + 1];
    m.nodes.x[3 * i] = X * 1.002 + 1e-3 * std::sin(40 * Y);
    m.nodes.x[3 * i + 1] = Y * (1.0 - 1e-3 * std::cos(7 * X));
    m.nodes.x[3 * i + 2] = 1e-3 * std::sin(30 * X) * std::sin(20 * Y);
    for (int k = 0; k < 3; ++k) m.nodes.v[3 * i + k] = 0.1 * std::sin(13.0 * i + 5.0 * k);
  }
  return s;
}

using Forces = test::MembraneEvaluation;

Forces evaluate(const Model& m, const MembraneForces& mf, int threads) {
  return test::evaluateMembranes(m, mf, threads);
}

double maxRelDiff(const std::vector<double>& a, const std::vector<double>& ref) {
  double diff = 0, scale = 0;
  for (std::size_t i = 0; i < ref.size(); ++i)
    diff = std::max(diff, std::abs(a[i] - ref[i])), scale = std::max(scale, std::abs(ref[i]));
  return diff / scale;
}

std::string errorOf(const std::string& yaml) {
  try {
    loadSceneFromString(yaml, "case.yaml");
  } catch (const fsi::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

// 2, 3 and 5 shares (the shares' node bands overlap; 3 and 5 threads on fewer cores also run), with and
// without viscosity; the same object evaluated again with another count re-partitions.
TEST(Threads, MembraneKernelEqualsSerial) {
  if (!threadsAvailable()) GTEST_SKIP() << "built without OpenMP";
  const Scene s = rippledSheet(32);  // 4096 triangles, 2113 nodes
  const Model& m = *s.model;
  ASSERT_GE(m.membranes.count, kMinParallelItems);
  for (const ElementDamping& d : {ElementDamping{}, ElementDamping{2.0e-6, 0.06}}) {
    const MembraneForces mf(m.membranes, d);
    const Forces serial = evaluate(m, mf, 1);
    for (int threads : {2, 3, 5, 2}) {
      const Forces par = evaluate(m, mf, threads);
      EXPECT_LE(maxRelDiff(par.f, serial.f), 1e-12) << threads << " threads";
      EXPECT_LE(std::abs(par.energy - serial.energy), 1e-12 * serial.energy) << threads << " threads";
      EXPECT_GT(serial.energy, 0.0);
      EXPECT_EQ(par.dt, serial.dt) << threads << " threads";  // a minimum: no rounding
    }
  }
}

// Whole central-difference steps (threaded kernel and node sweep): positions, velocities and the energy
// ledger after 40 steps agree with the serial run to round-off.
TEST(Threads, StepsEqualSerial) {
  if (!threadsAvailable()) GTEST_SKIP() << "built without OpenMP";
  Scene serial = rippledSheet(32);
  Scene threaded = rippledSheet(32, "solver: {threads: 2}");
  ASSERT_EQ(threaded.time.integrator.threads, 2);
  ASSERT_EQ(serial.time.integrator.threads, 1);
  ASSERT_GE(serial.model->nodes.count, kMinParallelItems);  // the node sweep is threaded too
  CentralDifference a(*serial.model, serial.effectList(), serial.constraints, serial.time.integrator);
  CentralDifference b(*threaded.model, threaded.effectList(), threaded.constraints, threaded.time.integrator);
  for (int i = 0; i < 40; ++i) {
    ASSERT_TRUE(a.step(1.0, i % 10 == 0));
    ASSERT_TRUE(b.step(1.0, i % 10 == 0));
  }
  const Nodes& na = serial.model->nodes;
  const Nodes& nb = threaded.model->nodes;
  std::vector<double> ua(na.x.size()), ub(nb.x.size());
  for (std::size_t d = 0; d < ua.size(); ++d) ua[d] = na.x[d] - na.X[d], ub[d] = nb.x[d] - nb.X[d];
  EXPECT_LE(maxRelDiff(ub, ua), 1e-11);
  EXPECT_LE(maxRelDiff(nb.v, na.v), 1e-11);
  EXPECT_NEAR(b.energy().kinetic, a.energy().kinetic, 1e-11 * a.energy().kinetic);
  EXPECT_NEAR(b.energy().strain, a.energy().strain, 1e-11 * a.energy().strain);
  EXPECT_EQ(b.lastDt(), a.lastDt());
}

TEST(Threads, SceneKeyIsChecked) {
  using fsi::test::drumScene;
  const std::string time = "time: {end: 0.001}\n";
  std::string e = errorOf(drumScene("solver: {threads: 0}\n" + time));
  EXPECT_NE(e.find("case.yaml:9:"), std::string::npos) << e;
  EXPECT_NE(e.find("solver.threads"), std::string::npos) << e;
  e = errorOf(drumScene("solver: {threads: two}\n" + time));
  EXPECT_NE(e.find("solver.threads"), std::string::npos) << e;
  e = errorOf(drumScene("solver: {thread: 2}\n" + time));
  EXPECT_NE(e.find("threads"), std::string::npos) << e;  // the "did you mean"
  // Without the key: one thread, whatever OMP_NUM_THREADS says.
  EXPECT_EQ(loadSceneFromString(drumScene(time), "case.yaml").time.integrator.threads, 1);
  if (threadsAvailable()) {
    const Scene s = loadSceneFromString(drumScene("solver: {threads: 2}\n" + time), "case.yaml");
    EXPECT_EQ(s.time.integrator.threads, 2);
    EXPECT_EQ(s.solver.type, SolverControl::Type::ExplicitDynamics);  // type defaults to explicit dynamics
    const Scene dr =
        loadSceneFromString(drumScene("solver: {type: dynamic_relaxation, threads: 2}\n"), "case.yaml");
    EXPECT_EQ(dr.solver.relaxation.threads, 2);
  } else {
    e = errorOf(drumScene("solver: {threads: 2}\n" + time));
    EXPECT_NE(e.find("OpenMP"), std::string::npos) << e;
  }
}
