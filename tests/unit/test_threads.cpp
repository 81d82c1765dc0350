// Threads (scene key solver.threads): the threaded force evaluation (membrane kernel, cable kernel, pressure
// loads, the effects that do not split) and node sweep give the serial results to round-off (only the order
// of the sums at the nodes and of the energy sums differs), and the key is checked like every other scene
// key.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "CabledSheet.hpp"
#include "ForceDifference.hpp"
#include "MembraneEvaluation.hpp"
#include "TestScenes.hpp"
#include "structure/effects/ExternalLoads.hpp"
#include "structure/effects/FabricBending.hpp"
#include "structure/effects/InterfacePressure.hpp"
#include "structure/effects/PressureDistribution.hpp"
#include "structure/effects/ThreadedForces.hpp"
#include "structure/effects/Threads.hpp"
#include "structure/elements/BuildModel.hpp"
#include "structure/elements/CableForces.hpp"
#include "structure/elements/MembraneForces.hpp"
#include "structure/integrate/CentralDifference.hpp"
#include "structure/integrate/DynamicRelaxation.hpp"
#include "structure/model/Error.hpp"
#include "structure/scene/Generators.hpp"
#include "structure/scene/Scene.hpp"

using namespace fsi::structure;

namespace {

// Divisions of a sheet of 4 n² triangles just above kMinParallelItems: the smallest mesh that is threaded.
int aboveThreshold() {
  return int(std::ceil(std::sqrt(kMinParallelItems / 4.0))) + 1;
}

// A clamped, pressurised sheet of 4 n² triangles, rippled into a mix of taut, wrinkled and slack triangles,
// with velocities for the viscous stresses.
Scene rippledSheet(int n, const std::string& extra = "", const std::string& extraEffects = "") {
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
{2}
time: {{end: 1.0}}
{1}
)",
                                            n, extra, extraEffects),
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

using test::largestRelativeDifference;

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
  const Scene s = rippledSheet(aboveThreshold());
  const Model& m = *s.model;
  ASSERT_GE(m.membranes.count, kMinParallelItems);
  for (const ElementDamping& d : {ElementDamping{}, ElementDamping{2.0e-6, 0.06}}) {
    const MembraneForces mf(m.membranes, d);
    const Forces serial = evaluate(m, mf, 1);
    for (int threads : {2, 3, 5}) {
      const Forces par = evaluate(m, mf, threads);
      ASSERT_EQ(par.shares, threads);  // really split
      EXPECT_LE(largestRelativeDifference(par.f, serial.f), 1e-12) << threads << " threads";
      EXPECT_LE(std::abs(par.energy - serial.energy), 1e-12 * serial.energy) << threads << " threads";
      EXPECT_GT(serial.energy, 0.0);
      EXPECT_EQ(par.dt, serial.dt) << threads << " threads";  // a minimum: no rounding
    }
  }
}

namespace {

// Every effect of `effects` at the model's state, serially (evaluateEffects) or on `threads` shares.
struct Evaluation {
  std::vector<double> fint, fext;
  double energy = 0, dt = 0;
  int shares = 1;
};
Evaluation evaluateAll(const Model& m, const std::vector<const Effect*>& effects, int threads) {
  Nodes n = m.nodes;
  ThreadedForces tf(effects, threads, n.count);
  const ForceContext ctx = tf.evaluate(n, 0.25, 1.0, true);
  return {n.fint, n.fext, ctx.strainEnergy, ctx.minStableDt, tf.shares()};
}

}  // namespace

// The pressure loads split like the membrane kernel: a follower pressure, a follower pressure distribution,
// a dead one and the flow's interface load (nodal pressures; nodal forces), each alone (a split effect of
// its own decides the threading), on 2, 3 and 5 shares.
TEST(Threads, PressureForcesEqualSerial) {
  if (!threadsAvailable()) GTEST_SKIP() << "built without OpenMP";
  const Scene s = rippledSheet(aboveThreshold());
  const Model& m = *s.model;
  const std::vector<int>& conn = m.membranes.conn;
  std::vector<double> values(std::size_t(m.membranes.count));
  for (std::size_t e = 0; e < values.size(); ++e) values[e] = 50.0 + 30.0 * std::sin(0.37 * double(e));
  const FollowerPressure follower("sheet", conn, 100.0, TimeFunction::constant());
  const PressureDistribution field("field", conn, values, TimeFunction::constant());
  const PressureDistribution dead =
      PressureDistribution::dead("dead", conn, values, TimeFunction::constant(), m.nodes.X);
  // The flow's load as the coupling delivers it: a pressure per interface node, and nodal forces.
  std::vector<int> all(std::size_t(m.nodes.count));
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = int(i);
  InterfaceLoad pressure{InterfaceLoadKind::Pressure, {}}, nodal{InterfaceLoadKind::NodalForces, {}};
  for (std::size_t i = 0; i < all.size(); ++i) {
    pressure.values.push_back(80.0 + 20.0 * std::cos(0.11 * double(i)));
    for (int k = 0; k < 3; ++k) nodal.values.push_back(std::sin(0.7 * double(i) + k));
  }
  const InterfacePressure flowPressure(conn, all, pressure), flowForces(conn, all, nodal);
  for (const Effect* e : {static_cast<const Effect*>(&follower), static_cast<const Effect*>(&field),
                          static_cast<const Effect*>(&dead), static_cast<const Effect*>(&flowPressure),
                          static_cast<const Effect*>(&flowForces)}) {
    ASSERT_GE(e->connectivity().items, kMinParallelItems);
    const Evaluation serial = evaluateAll(m, {e}, 1);
    ASSERT_GT(*std::max_element(serial.fext.begin(), serial.fext.end()), 0.0);
    for (int threads : {2, 3, 5}) {
      const Evaluation par = evaluateAll(m, {e}, threads);
      ASSERT_EQ(par.shares, threads);
      EXPECT_LE(largestRelativeDifference(par.fext, serial.fext), 1e-12)
          << e->name() << ", " << threads << " threads";
    }
  }
}

namespace {

// A square net of n x n nodes with a cable along every grid segment (2 n (n − 1) cables), stretched by
// 0.3 % with ripples (about 10 % of the cables slack), with velocities; with sheetDivisions > 0 also a
// membrane sheet of 4 d² triangles in the same model (its own nodes, rippled the same way), so that two
// split effects share the threads.
Model cableNet(int n, int sheetDivisions = 0) {
  std::vector<MeshInput> meshes;
  MeshInput net;
  net.mesh.name = "net";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) net.mesh.points.push_back({double(i) / (n - 1), double(j) / (n - 1), 0.0});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (i + 1 < n) net.mesh.lines.push_back({j * n + i, j * n + i + 1});
      if (j + 1 < n) net.mesh.lines.push_back({j * n + i, (j + 1) * n + i});
    }
  net.cableMaterial = 0;
  meshes.push_back(net);
  if (sheetDivisions > 0) {
    RectangleParams p;
    p.size = {1.0, 1.0};
    p.divisions = {sheetDivisions, sheetDivisions};
    p.center = {0.5, 0.5, 2.0};
    p.pattern = "cross";
    MeshInput sheet;
    sheet.mesh = rectangle(p, "sheet");
    sheet.membraneMaterial = 0;
    meshes.push_back(sheet);
  }
  Model m = buildModel(meshes, {MembraneMaterial{"film", 1.0e9, 0.3, 1.0e-3, 1000, true}},
                       {CableMaterial{"line", 7.0e10, 1.26e-5, 1440}});
  for (int i = 0; i < m.nodes.count; ++i) {
    const double X = m.nodes.X[3 * i], Y = m.nodes.X[3 * i + 1], Z = m.nodes.X[3 * i + 2];
    m.nodes.x[3 * i] = 1.003 * X + 8e-5 * std::sin(50 * X) + 1e-4 * std::sin(40 * Y);
    m.nodes.x[3 * i + 1] = 1.003 * Y + 6e-5 * std::sin(50 * Y);
    m.nodes.x[3 * i + 2] = Z + 1e-3 * std::sin(30 * X) * std::sin(20 * Y);
    for (int k = 0; k < 3; ++k) m.nodes.v[3 * i + k] = 0.1 * std::sin(13.0 * i + 5.0 * k);
  }
  return m;
}

// Grid side of the smallest net with kMinParallelItems cables.
int netAboveThreshold() {
  int n = 2;
  while (2 * n * (n - 1) < kMinParallelItems) ++n;
  return n;
}

}  // namespace

// The cable kernel splits like the membrane kernel once it has kMinParallelItems cables: forces, strain
// energy and stable step on 2, 3 and 5 shares as serially, with and without viscosity, batched and per
// cable; below the threshold it does not split (and alone stays serial).
TEST(Threads, CableForcesEqualSerial) {
  if (!threadsAvailable()) GTEST_SKIP() << "built without OpenMP";
  const Model m = cableNet(netAboveThreshold());
  ASSERT_GE(m.cables.count, kMinParallelItems);
  std::vector<double> T;
  cableTensions(m.cables, m.nodes.x.data(), T);
  const long slack = std::count(T.begin(), T.end(), 0.0);
  ASSERT_GT(slack, m.cables.count / 20);  // a mix of slack and taut cables
  ASSERT_LT(slack, m.cables.count / 2);
  for (const ElementDamping& d : {ElementDamping{}, ElementDamping{2.0e-6, 0.06}})
    for (CableKernel kernel : {CableKernel::Batched, CableKernel::PerElement}) {
      const CableForces cf(m.cables, d, kernel);
      ASSERT_EQ(cf.connectivity().items, m.cables.count);
      const Evaluation serial = evaluateAll(m, {&cf}, 1);
      ASSERT_LE(serial.shares, 1);  // serial (no shares)
      ASSERT_GT(serial.energy, 0.0);
      for (int threads : {2, 3, 5}) {
        const std::string what = std::to_string(threads) + " threads" + (d.enabled() ? ", viscous" : "") +
                                 (kernel == CableKernel::Batched ? "" : ", per cable");
        const Evaluation par = evaluateAll(m, {&cf}, threads);
        ASSERT_EQ(par.shares, threads) << what;  // really split
        EXPECT_LE(largestRelativeDifference(par.fint, serial.fint), 1e-12) << what;
        EXPECT_LE(std::abs(par.energy - serial.energy), 1e-12 * serial.energy) << what;
        EXPECT_EQ(par.dt, serial.dt) << what;  // a minimum: no rounding
      }
    }
  const Model small = cableNet(netAboveThreshold() - 1);
  ASSERT_LT(small.cables.count, kMinParallelItems);
  const CableForces cf(small.cables, {});
  EXPECT_EQ(ThreadedForces({&cf}, 2, small.nodes.count).splitElements(), 0);  // runs whole
  EXPECT_LE(evaluateAll(small, {&cf}, 2).shares, 1);                          // stays serial
}

// Cables and membranes both split in one evaluation (their shares' node bands differ: the net's nodes and
// the sheet's); a small cable set beside a large membrane does not split and runs whole on the first share.
TEST(Threads, CablesAndMembranesEqualSerial) {
  if (!threadsAvailable()) GTEST_SKIP() << "built without OpenMP";
  for (int netSide : {netAboveThreshold(), 12}) {
    const Model m = cableNet(netSide, aboveThreshold());
    ASSERT_GE(m.membranes.count, kMinParallelItems);
    const ElementDamping d{2.0e-6, 0.06};
    const CableForces cf(m.cables, d);
    const MembraneForces mf(m.membranes, d);
    // A small cable set runs whole (scattered), a large one splits with the membranes.
    EXPECT_EQ(ThreadedForces({&mf, &cf}, 2, m.nodes.count).splitElements(),
              m.membranes.count + (m.cables.count >= kMinParallelItems ? m.cables.count : 0));
    const Evaluation serial = evaluateAll(m, {&mf, &cf}, 1);
    for (int threads : {2, 3}) {
      const std::string what =
          std::to_string(m.cables.count) + " cables, " + std::to_string(threads) + " threads";
      const Evaluation par = evaluateAll(m, {&mf, &cf}, threads);
      ASSERT_EQ(par.shares, threads) << what;
      EXPECT_LE(largestRelativeDifference(par.fint, serial.fint), 1e-12) << what;
      EXPECT_LE(std::abs(par.energy - serial.energy), 1e-12 * serial.energy) << what;
      EXPECT_EQ(par.dt, serial.dt) << what;
    }
  }
}

// A whole evaluation of a scene's effects: the membrane kernel, the pressure and gravity split, a nodal
// force (which does not split) runs on the first thread after the shares; internal and external forces,
// strain energy and the stable step as serially.
TEST(Threads, AllEffectsEqualSerial) {
  if (!threadsAvailable()) GTEST_SKIP() << "built without OpenMP";
  const Scene s = rippledSheet(
      aboveThreshold(), "", "  stiffness_damping: {beta: 2.0e-6}\n  gravity: {acceleration: [0, 0, -9.81]}");
  const Model& m = *s.model;
  const NodalForces nodal("spread", {0, m.nodes.count / 3, m.nodes.count - 1}, {1.0, -2.0, 3.0},
                          TimeFunction::constant());
  std::vector<const Effect*> effects = s.effectList();
  effects.push_back(&nodal);
  int split = 0, whole = 0;
  for (const Effect* e : effects) (e->connectivity().items > 0 ? split : whole) += 1;
  ASSERT_GE(split, 3);  // membrane, pressure and gravity
  ASSERT_GE(whole, 1);  // the nodal force
  const Evaluation serial = evaluateAll(m, effects, 1);
  for (int threads : {2, 3, 5}) {
    const Evaluation par = evaluateAll(m, effects, threads);
    ASSERT_EQ(par.shares, threads);
    EXPECT_LE(largestRelativeDifference(par.fint, serial.fint), 1e-12) << threads << " threads";
    EXPECT_LE(largestRelativeDifference(par.fext, serial.fext), 1e-12) << threads << " threads";
    EXPECT_NEAR(par.energy, serial.energy, 1e-12 * serial.energy) << threads << " threads";
    EXPECT_EQ(par.dt, serial.dt) << threads << " threads";
  }
}

// The fabric's bending splits over its hinges in two passes (every hinge's angle, a barrier, then each
// hinge's moment from its two triangles): with the membranes and the pressure, in a whole evaluation and in
// 40 central-difference steps, on 2, 3 and 5 shares as serially.
TEST(Threads, BendingEqualsSerial) {
  if (!threadsAvailable()) GTEST_SKIP() << "built without OpenMP";
  const std::string bending = "  bending: {triangles: sheet, rigidity: 1.0e-3}";
  const Scene s = rippledSheet(aboveThreshold(), "", bending);
  const Model& m = *s.model;
  const std::vector<const Effect*> effects = s.effectList();
  const Effect* bend = nullptr;
  for (const Effect* e : effects)
    if (e->name().rfind("bending", 0) == 0) bend = e;
  ASSERT_NE(bend, nullptr);
  ASSERT_GT(bend->connectivity().items, m.membranes.count);  // hinges: about 1.5 per triangle
  ASSERT_TRUE(bend->connectivity().prepass);
  const Evaluation serial = evaluateAll(m, {bend}, 1), serialAll = evaluateAll(m, effects, 1);
  ASSERT_GT(serial.energy, 0.0);
  // ½ Δθᵀ K Δθ summed over the hinges: the energy summed over the triangles.
  EXPECT_NEAR(serial.energy, dynamic_cast<const FabricBending&>(*bend).energy(m.nodes.x.data()),
              1e-12 * serial.energy);
  for (int threads : {2, 3, 5}) {
    const Evaluation par = evaluateAll(m, {bend}, threads), parAll = evaluateAll(m, effects, threads);
    ASSERT_EQ(par.shares, threads);
    EXPECT_LE(largestRelativeDifference(par.fint, serial.fint), 1e-12) << threads << " threads";
    EXPECT_NEAR(par.energy, serial.energy, 1e-12 * serial.energy) << threads << " threads";
    EXPECT_EQ(par.dt, serial.dt) << threads << " threads";
    EXPECT_LE(largestRelativeDifference(parAll.fint, serialAll.fint), 1e-12) << threads << " threads";
    EXPECT_NEAR(parAll.energy, serialAll.energy, 1e-12 * serialAll.energy) << threads << " threads";
  }
  Scene one = rippledSheet(aboveThreshold(), "", bending);
  CentralDifference a(*one.model, one.effectList(), one.constraints, one.time.integrator);
  for (int i = 0; i < 40; ++i) ASSERT_TRUE(a.step(1.0, i % 10 == 0));
  for (int threads : {2, 5}) {
    Scene many = rippledSheet(aboveThreshold(), fmt::format("solver: {{threads: {}}}", threads), bending);
    CentralDifference b(*many.model, many.effectList(), many.constraints, many.time.integrator);
    for (int i = 0; i < 40; ++i) ASSERT_TRUE(b.step(1.0, i % 10 == 0));
    EXPECT_LE(largestRelativeDifference(many.model->nodes.v, one.model->nodes.v), 1e-11) << threads;
    EXPECT_NEAR(b.energy().strain, a.energy().strain, 1e-11 * a.energy().scale()) << threads;
  }
}

// Gravity splits over the nodes when something else is threaded, but its m g per node is too cheap to be
// worth waking threads for: a model with many nodes and a small membrane or cable set stays serial.
TEST(Threads, GravityAloneDoesNotThread) {
  if (!threadsAvailable()) GTEST_SKIP() << "built without OpenMP";
  const Scene s = rippledSheet(aboveThreshold(), "", "  gravity: {acceleration: [0, 0, -9.81]}");
  const Model& m = *s.model;
  // Gravity over the nodes' masses repeated past the threshold on its own.
  std::vector<double> mass = m.nodes.mass;
  while (int(mass.size()) < kMinParallelItems)
    mass.insert(mass.end(), m.nodes.mass.begin(), m.nodes.mass.end());
  const Gravity many(mass, {0, 0, -9.81}, TimeFunction::constant());
  ASSERT_GE(many.connectivity().items, kMinParallelItems);
  ASSERT_TRUE(many.connectivity().light);
  EXPECT_TRUE(ThreadedForces({&many}, 2, many.connectivity().items).serial());
  // With the membranes it splits: the scene's evaluation threads, gravity among the split effects.
  const ThreadedForces all(s.effectList(), 2, m.nodes.count);
  EXPECT_EQ(all.shares(), 2);
  EXPECT_EQ(all.splitElements(), 2L * m.membranes.count + m.nodes.count);  // membranes, pressure, gravity
}

// Whole central-difference steps (threaded forces and node sweep in one parallel region): positions,
// velocities and the energy ledger after 40 steps agree with the serial run to round-off, on 2, 3 and 5
// threads.
TEST(Threads, StepsEqualSerial) {
  if (!threadsAvailable()) GTEST_SKIP() << "built without OpenMP";
  const int n = aboveThreshold();
  Scene serial = rippledSheet(n);
  ASSERT_EQ(serial.time.integrator.threads, 1);
  CentralDifference a(*serial.model, serial.effectList(), serial.constraints, serial.time.integrator);
  for (int i = 0; i < 40; ++i) ASSERT_TRUE(a.step(1.0, i % 10 == 0));
  const Nodes& na = serial.model->nodes;
  const EnergyLedger& la = a.energy();
  for (int threads : {2, 3, 5}) {
    Scene threaded = rippledSheet(n, fmt::format("solver: {{threads: {}}}", threads));
    ASSERT_EQ(threaded.time.integrator.threads, threads);
    CentralDifference b(*threaded.model, threaded.effectList(), threaded.constraints,
                        threaded.time.integrator);
    for (int i = 0; i < 40; ++i) ASSERT_TRUE(b.step(1.0, i % 10 == 0));
    const Nodes& nb = threaded.model->nodes;
    std::vector<double> ua(na.x.size()), ub(nb.x.size());
    for (std::size_t d = 0; d < ua.size(); ++d) ua[d] = na.x[d] - na.X[d], ub[d] = nb.x[d] - nb.X[d];
    EXPECT_LE(largestRelativeDifference(ub, ua), 1e-11) << threads << " threads";
    EXPECT_LE(largestRelativeDifference(nb.v, na.v), 1e-11) << threads << " threads";
    // The bookkeeping: every term of the balance, the balance itself and the step.
    const EnergyLedger& lb = b.energy();
    const double scale = la.scale();
    ASSERT_GT(scale, 0.0);
    EXPECT_NEAR(lb.kinetic, la.kinetic, 1e-11 * scale) << threads << " threads";
    EXPECT_NEAR(lb.kineticProduct, la.kineticProduct, 1e-11 * scale) << threads << " threads";
    EXPECT_NEAR(lb.strain, la.strain, 1e-11 * scale) << threads << " threads";
    EXPECT_NEAR(lb.externalWork, la.externalWork, 1e-11 * scale) << threads << " threads";
    EXPECT_NEAR(lb.internalWork, la.internalWork, 1e-11 * scale) << threads << " threads";
    EXPECT_NEAR(lb.massDamping, la.massDamping, 1e-11 * scale) << threads << " threads";
    EXPECT_LE(lb.balanceError(), 1e-12) << threads << " threads";
    EXPECT_EQ(b.lastDt(), a.lastDt()) << threads << " threads";
    // The stable step of the current geometry, which differs by round-off after 40 steps (the step taken is
    // the limit's whole fraction, equal above).
    EXPECT_NEAR(b.stableDt(), a.stableDt(), 1e-11 * a.stableDt()) << threads << " threads";
  }
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

namespace {

struct Relaxed {
  RelaxationResult r;
  std::vector<double> u;  ///< displacement x − X at the end
};

// The scene relaxed from its reference state on `threads` threads.
Relaxed relax(Scene& s, int threads) {
  Nodes& N = s.model->nodes;
  N.x = N.X;
  std::fill(N.v.begin(), N.v.end(), 0.0);
  RelaxationSettings rs = s.solver.relaxation;
  rs.threads = threads;
  DynamicRelaxation dr(*s.model, s.effectList(), s.constraints, rs);
  Relaxed out;
  out.r = dr.run();
  out.u.resize(N.x.size());
  for (std::size_t d = 0; d < N.x.size(); ++d) out.u[d] = N.x[d] - N.X[d];
  return out;
}

}  // namespace

// Dynamic relaxation with its node loops in the force evaluation's parallel region (frequency test, norms,
// kinetic-energy trial and update, back-step, sliders; sums per node range added in range order) against the
// serial relaxation: the cabled sheet of tests/unit/CabledSheet.hpp (10 000 triangles, 300 cables) with an
// oblique symmetry plane along its diagonal (101 sliding nodes, on both threads' ranges), on 2 and 3 threads.
// Kinetic damping to convergence, with the masses fixed (update and back-step in the region) and recomputed
// at every reset (back-step and mass refresh serial, then the region): the same iterations and resets, the
// static state to 1e-10 (measured 0.9–2.6e-13). Viscous damping (the update before the forces, in the
// region) for its first 100 iterations only: on this sheet its trajectory amplifies round-off, serial runs
// included (λ changed by 1 ulp: 2391 instead of 2911 iterations to 1e-6, without the sliders), so only the
// start is comparable (measured 1.3e-12).
TEST(Threads, RelaxationEqualsSerial) {
  if (!threadsAvailable()) GTEST_SKIP() << "built without OpenMP";
  struct Variant {
    std::string solver;
    long maxIterations;
    std::vector<int> threads;
  };
  const std::vector<Variant> variants{{"tolerance: 1.0e-6", 0, {2, 3}},
                                      {"tolerance: 1.0e-6, update_masses: true", 0, {2}},
                                      {"tolerance: 1.0e-6, damping: viscous", 100, {2, 3}}};
  for (const Variant& v : variants) {
    const std::filesystem::path dir = fsi::test::outDir("cabled-sheet");
    const std::string yaml =
        fsi::test::writeCabledSheet(dir, 50, v.solver, "  - {symmetry: {normal: [1, -1, 0]}}\n");
    Scene s = loadSceneFromString(yaml, (dir / "sheet.yaml").string());
    ASSERT_GE(s.model->membranes.count, 10000);
    ASSERT_GT(s.model->cables.count, 0);
    ASSERT_GT(s.constraints.sliders.size(), 50u);
    if (v.maxIterations > 0) s.solver.relaxation.maxIterations = v.maxIterations;
    const Relaxed serial = relax(s, 1);
    if (v.maxIterations > 0) {
      ASSERT_EQ(serial.r.iterations, v.maxIterations) << v.solver;
    } else {
      ASSERT_EQ(serial.r.reason, StopReason::Static) << v.solver;
      ASSERT_GT(serial.r.kineticResets, 5) << v.solver;
    }
    for (int threads : v.threads) {
      ASSERT_EQ(ThreadedForces(s.effectList(), threads, s.model->nodes.count).shares(), threads);
      const Relaxed par = relax(s, threads);
      EXPECT_EQ(par.r.reason, serial.r.reason) << v.solver << ", " << threads << " threads";
      EXPECT_EQ(par.r.iterations, serial.r.iterations) << v.solver << ", " << threads << " threads";
      EXPECT_EQ(par.r.kineticResets, serial.r.kineticResets) << v.solver << ", " << threads << " threads";
      EXPECT_EQ(par.r.massIncreases, serial.r.massIncreases) << v.solver << ", " << threads << " threads";
      EXPECT_LE(largestRelativeDifference(par.u, serial.u), 1e-10)
          << v.solver << ", " << threads << " threads";
    }
  }
}

// The threaded relaxation does not depend on the scheduling: 5 shares run by one thread (OneThreadScope) give
// the same bits as 5 threads on fewer cores, whose shares finish in varying order. Viscous damping, whose
// coefficient comes from the node loops' sums (kinetic damping's sums only decide the resets), for 400
// iterations: every iteration's sums bit for bit (a sum added in the order the threads finish changes its
// last bit now and then) and the end state (the trajectory amplifies such a bit).
TEST(Threads, RelaxationDoesNotDependOnTheScheduling) {
  if (!threadsAvailable()) GTEST_SKIP() << "built without OpenMP";
  const std::filesystem::path dir = fsi::test::outDir("cabled-sheet");
  const std::string yaml = fsi::test::writeCabledSheet(dir, 50, "damping: viscous, max_iterations: 400");
  Scene s = loadSceneFromString(yaml, (dir / "sheet.yaml").string());
  ASSERT_EQ(ThreadedForces(s.effectList(), 5, s.model->nodes.count).shares(), 5);
  const Relaxed par = relax(s, 5);
  Relaxed one;
  {
    const OneThreadScope scope;
    one = relax(s, 5);
  }
  ASSERT_EQ(par.r.iterations, 400);
  ASSERT_EQ(one.r.history.size(), par.r.history.size());
  // Every iteration's kinetic energy (a sum over the nodes) and ratios, bit for bit, and the end state.
  int differing = 0;
  for (std::size_t i = 0; i < par.r.history.size(); ++i) {
    const RelaxationRecord &a = one.r.history[i], &b = par.r.history[i];
    differing += a.kinetic != b.kinetic || a.residualRatio != b.residualRatio ||
                 a.energyRatio != b.energyRatio || a.strain != b.strain;
  }
  EXPECT_EQ(differing, 0) << "iterations whose sums depend on the scheduling";
  EXPECT_EQ(largestRelativeDifference(one.u, par.u), 0.0);
}

// The seam: on a sheet whose nodes follow the Morton curve and whose triangles are sorted by their lowest
// node (what every model gets), almost every element writes straight into its share's band of the node
// arrays; only those near a band boundary go through a buffer. Between two bands of this sheet the boundary
// is a straight row of cells, 4 triangles each: ≈ 100 × 4 of 40 000 triangles per effect (1 %), 2.5 % at
// most with whole batches of the kernel. More bands have more boundaries: 2.5 % per boundary. The bands
// split the nodes about evenly (they also share the node sweep).
TEST(Threads, SortedElementsWriteIntoTheirBand) {
  if (!threadsAvailable()) GTEST_SKIP() << "built without OpenMP";
  const Scene s = rippledSheet(100);  // 40 000 triangles
  const Model& m = *s.model;
  for (int threads : {2, 3, 5}) {
    const ThreadedForces tf(s.effectList(), threads, m.nodes.count);
    ASSERT_EQ(tf.shares(), threads);
    EXPECT_EQ(tf.splitElements(), 2L * m.membranes.count);  // membranes and pressure
    EXPECT_LE(double(tf.seamElements()), 0.025 * (threads - 1) * double(tf.splitElements())) << threads;
    EXPECT_GT(tf.seamElements(), 0) << threads;  // the bands do meet
    for (int sh = 0; sh < threads; ++sh)
      EXPECT_NEAR(tf.nodeEnd(sh) - tf.nodeBegin(sh), double(m.nodes.count) / threads,
                  0.1 * m.nodes.count / threads)
          << threads << " shares, band " << sh;
  }
}

// Elements in no useful order (a pressure load over the sheet's triangles shuffled, the flow's nodal
// forces over its nodes shuffled) reach across all bands: most go through the buffers, and the forces
// are still the serial ones.
TEST(Threads, ShuffledElementsEqualSerial) {
  if (!threadsAvailable()) GTEST_SKIP() << "built without OpenMP";
  const Scene s = rippledSheet(aboveThreshold());
  const Model& m = *s.model;
  const int nt = m.membranes.count;
  std::vector<int> order(static_cast<std::size_t>(nt));
  std::vector<int> conn;
  for (int e = 0; e < nt; ++e) order[std::size_t(e)] = int((7919L * e) % nt);  // nt is not a multiple
  ASSERT_NE(nt % 7919, 0);                                                     // a permutation: 7919 is prime
  for (int e : order)
    for (int k = 0; k < 3; ++k) conn.push_back(m.membranes.conn[3 * std::size_t(e) + k]);
  std::vector<int> nodes(std::size_t(m.nodes.count));
  for (std::size_t i = 0; i < nodes.size(); ++i) nodes[i] = int((104729L * long(i)) % m.nodes.count);
  InterfaceLoad forces{InterfaceLoadKind::NodalForces, {}};
  for (std::size_t i = 0; i < nodes.size(); ++i)
    for (int k = 0; k < 3; ++k) forces.values.push_back(std::sin(0.7 * double(i) + k));
  const FollowerPressure pressure("shuffled", conn, 100.0, TimeFunction::constant());
  const InterfacePressure flow(conn, nodes, forces);
  const std::vector<const Effect*> effects{&pressure, &flow};
  const Evaluation serial = evaluateAll(m, effects, 1);
  for (int threads : {2, 3}) {
    const ThreadedForces tf(effects, threads, m.nodes.count);
    EXPECT_GT(double(tf.seamElements()), 0.5 * double(tf.splitElements())) << threads;
    const Evaluation par = evaluateAll(m, effects, threads);
    ASSERT_EQ(par.shares, threads);
    EXPECT_LE(largestRelativeDifference(par.fext, serial.fext), 1e-12) << threads << " threads";
  }
}

namespace {

// The bits of every force component of two evaluations that differ, as dofs.
long differingDofs(const std::vector<double>& a, const std::vector<double>& b) {
  long n = 0;
  for (std::size_t d = 0; d < a.size(); ++d) n += a[d] != b[d];
  return n;
}

}  // namespace

// Membranes, cables (enough to split), the fabric's bending (its first pass and working memory) and a
// follower pressure in one evaluation, the assembler's threaded sums against the serial ones. Threads
// change the sums only at the seams: every node that no seam element writes to (the elements that reach
// across a band boundary and go through a share's buffer) gets its terms in the serial order, so its forces
// are the serial ones bit for bit; at the seam nodes the buffer's partial sum is added last (round-off),
// as are the energy's partial sums per share. And the threaded evaluation is deterministic: the same bits
// again, and with every share run by one thread (OneThreadScope) as by their own threads.
TEST(Threads, MembranesCablesBendingAreDeterministic) {
  if (!threadsAvailable()) GTEST_SKIP() << "built without OpenMP";
  const Model m = cableNet(netAboveThreshold(), aboveThreshold());
  ASSERT_GE(m.cables.count, kMinParallelItems);
  const ElementDamping d{2.0e-6, 0.06};
  const MembraneForces mf(m.membranes, d);
  const CableForces cf(m.cables, d);
  const FabricBending bend("sheet", m.membranes.conn, m.nodes.X, &m.nodes.mass, 1.0e-3);
  const FollowerPressure pressure("sheet", m.membranes.conn, 100.0, TimeFunction::constant());
  ASSERT_GE(bend.hinges(), kMinParallelItems);
  const std::vector<const Effect*> effects{&mf, &cf, &bend, &pressure};
  const Evaluation serial = evaluateAll(m, effects, 1);
  ASSERT_GT(serial.energy, 0.0);
  for (int threads : {2, 3, 5}) {
    const std::string what = std::to_string(threads) + " threads";
    const ThreadedForces tf(effects, threads, m.nodes.count);
    ASSERT_EQ(tf.shares(), threads) << what;
    ASSERT_EQ(tf.splitElements(), 2L * m.membranes.count + m.cables.count + bend.hinges()) << what;
    const Evaluation par = evaluateAll(m, effects, threads);
    EXPECT_LE(largestRelativeDifference(par.fint, serial.fint), 1e-12) << what;
    EXPECT_LE(largestRelativeDifference(par.fext, serial.fext), 1e-12) << what;
    EXPECT_NEAR(par.energy, serial.energy, 1e-12 * serial.energy) << what;
    EXPECT_EQ(par.dt, serial.dt) << what;
    // Bit for bit outside the seams: at most the seam elements' nodes (4 at most each) differ.
    const long seamDofs = 3 * 4 * tf.seamElements();
    EXPECT_LE(differingDofs(par.fint, serial.fint), seamDofs) << what;
    EXPECT_LE(differingDofs(par.fext, serial.fext), seamDofs) << what;
    // All but a few per cent of the dofs bit for bit (measured 2.6, 5.9 and 8.3 % of the internal forces'
    // on 2, 3 and 5 threads), and only where a seam element writes.
    EXPECT_LE(double(differingDofs(par.fint, serial.fint)), 0.05 * (threads - 1) * 3 * m.nodes.count) << what;
    // Deterministic: again, and with the shares one after the other on one thread.
    const Evaluation again = evaluateAll(m, effects, threads);
    Evaluation one;
    {
      const OneThreadScope scope;
      one = evaluateAll(m, effects, threads);
    }
    for (const Evaluation* e : {&again, static_cast<const Evaluation*>(&one)}) {
      EXPECT_EQ(differingDofs(e->fint, par.fint), 0) << what;
      EXPECT_EQ(differingDofs(e->fext, par.fext), 0) << what;
      EXPECT_EQ(e->energy, par.energy) << what;
      EXPECT_EQ(e->dt, par.dt) << what;
    }
  }
}

namespace {

// An effect written against the effect contract alone, knowing nothing of threads: linear springs between
// node pairs (tension k (L − L0), L0 the reference length), in batches of 3, with a first pass that puts
// every spring's unit direction and length into the caller's working memory; each spring's force also reads
// the length of another spring (its partner, half the set away), so that it needs the first pass of ALL
// springs, not only of its own range. It counts the evaluations of each spring and the ranges that do not
// start on a batch (instrumentation owned by the test).
class PairSprings final : public Effect {
 public:
  PairSprings(std::vector<int> pairs, const std::vector<double>& X, std::vector<std::atomic<int>>& visits,
              std::atomic<int>& misaligned)
      : pairs_(std::move(pairs)), visits_(visits), misaligned_(misaligned) {
    for (std::size_t i = 0; 2 * i < pairs_.size(); ++i) {
      const double* a = &X[3 * std::size_t(pairs_[2 * i])];
      const double* b = &X[3 * std::size_t(pairs_[2 * i + 1])];
      restLength_.push_back(std::sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) +
                                      (b[2] - a[2]) * (b[2] - a[2])));
    }
  }
  std::string name() const override { return "pair_springs"; }
  int springs() const { return int(restLength_.size()); }
  Connectivity connectivity() const override {
    Connectivity c;
    c.items = springs();
    c.nodesPerItem = 2;
    c.nodes = pairs_.data();
    c.batch = 3;
    c.prepass = true;
    c.scratch = 4 * std::size_t(springs());
    return c;
  }
  void addForces(ForceContext& ctx) const override {
    prepareRange(ctx, 0, springs());
    addRange(ctx, 0, springs());
  }
  void prepareRange(const ForceContext& ctx, int begin, int end) const override {
    for (int i = begin; i < end; ++i) {
      const double* a = &ctx.x[3 * std::size_t(pairs_[2 * std::size_t(i)])];
      const double* b = &ctx.x[3 * std::size_t(pairs_[2 * std::size_t(i) + 1])];
      double* s = &ctx.scratch[4 * std::size_t(i)];
      for (int k = 0; k < 3; ++k) s[k] = b[k] - a[k];
      s[3] = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
      for (int k = 0; k < 3; ++k) s[k] /= s[3];
    }
  }
  void addRange(ForceContext& ctx, int begin, int end) const override {
    if (begin % 3 != 0) ++misaligned_;
    const int n = springs();
    double energy = 0;
    for (int i = begin; i < end; ++i) {
      ++visits_[std::size_t(i)];
      const double* s = &ctx.scratch[4 * std::size_t(i)];
      const double partner = ctx.scratch[4 * std::size_t((i + n / 2) % n) + 3];
      const double stretch = s[3] - restLength_[std::size_t(i)];
      const double T = kStiffness * (1.0 + partner) * stretch;
      energy += 0.5 * kStiffness * (1.0 + partner) * stretch * stretch;
      double* fa = &ctx.fint[3 * std::size_t(pairs_[2 * std::size_t(i)])];
      double* fb = &ctx.fint[3 * std::size_t(pairs_[2 * std::size_t(i) + 1])];
      for (int k = 0; k < 3; ++k) fa[k] -= T * s[k], fb[k] += T * s[k];
    }
    if (ctx.wantEnergy) ctx.strainEnergy += energy;
  }

 private:
  static constexpr double kStiffness = 1.0e3;
  std::vector<int> pairs_;
  std::vector<double> restLength_;
  std::vector<std::atomic<int>>& visits_;
  std::atomic<int>& misaligned_;
};

}  // namespace

// The effect contract is all an effect needs to run threaded: a test effect that states its connectivity,
// batch, first pass and working memory (PairSprings) is split by the assembler into ranges that tile its
// items once per evaluation, start on whole batches, see every item's first pass, write into the bands and
// the seam buffers as the assembler chose (neighbouring springs and far-reaching ones), and give the serial
// forces to round-off on 2, 3 and 5 threads.
TEST(Threads, AnEffectOfTheContractIsThreadedByTheAssembler) {
  if (!threadsAvailable()) GTEST_SKIP() << "built without OpenMP";
  const Scene s = rippledSheet(aboveThreshold());
  const Model& m = *s.model;
  const int nn = m.nodes.count;
  // Sorted by their lower node, as a model's elements are: each node to its next three, and every 50th to
  // a far one (these reach across the bands).
  std::vector<int> pairs;
  for (int i = 0; i < nn; ++i) {
    for (int step = 1; step <= 3 && i + step < nn; ++step) pairs.insert(pairs.end(), {i, i + step});
    if (i % 50 == 0) pairs.insert(pairs.end(), {i, int((7919L * i + 13) % nn)});
  }
  if (pairs.size() / 2 % 3 == 0) pairs.insert(pairs.end(), {0, nn - 1});  // a last, partial batch
  std::vector<std::atomic<int>> visits(pairs.size() / 2);
  std::atomic<int> misaligned{0};
  const PairSprings springs(pairs, m.nodes.X, visits, misaligned);
  ASSERT_GE(springs.springs(), kMinParallelItems);
  ASSERT_NE(springs.springs() % 3, 0);
  const auto resetVisits = [&] {
    for (auto& v : visits) v = 0;
  };
  const Evaluation serial = evaluateAll(m, {&springs}, 1);
  ASSERT_GT(serial.energy, 0.0);
  ASSERT_GT(*std::max_element(serial.fint.begin(), serial.fint.end()), 0.0);
  for (int threads : {2, 3, 5}) {
    const std::string what = std::to_string(threads) + " threads";
    const ThreadedForces tf({&springs}, threads, nn);
    ASSERT_EQ(tf.shares(), threads) << what;
    EXPECT_GT(tf.seamElements(), 0) << what;                       // the far springs
    EXPECT_LT(tf.seamElements(), tf.splitElements() / 2) << what;  // the near ones write directly
    resetVisits();
    const Evaluation par = evaluateAll(m, {&springs}, threads);
    ASSERT_EQ(par.shares, threads) << what;
    EXPECT_TRUE(std::all_of(visits.begin(), visits.end(), [](const std::atomic<int>& v) { return v == 1; }))
        << what;
    EXPECT_EQ(misaligned.load(), 0) << what;
    EXPECT_LE(largestRelativeDifference(par.fint, serial.fint), 1e-12) << what;
    EXPECT_NEAR(par.energy, serial.energy, 1e-12 * serial.energy) << what;
  }
}
