// The energy ledger of the central-difference integrator: exact bookkeeping at every step (product-form
// kinetic energy, work in half steps, support reactions), checked against quantities computed independently
// of the ledger — the strain energy of the elements, the analytical work of a constant force, the analytical
// dissipation of a damped linear oscillator, the analytical work of a prescribed motion — and the instability
// checks built on it (growth of the step-to-step velocity energy, energy created in the elements).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "TestScenes.hpp"
#include "structure/integrate/CentralDifference.hpp"
#include "structure/run/Simulation.hpp"
#include "structure/scene/Scene.hpp"

using namespace fsi::structure;
namespace fs = std::filesystem;

namespace {

using fsi::test::outDir;

std::string replaceOnce(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  if (at == std::string::npos) throw std::logic_error("test scene: '" + from + "' not found");
  return s.replace(at, from.size(), to);
}

// Ten cable elements along x, held on the x axis, ends fixed: for axial motion a chain of linear springs
// (T = EA (L − L0)/L0 while taut, energy ½ EA/L0 (L − L0)²). Stable step L0/c = 1e-4 s.
const char* kChain = R"(materials:
  rope: {type: cable, young: 1.0e9, area: 1.0e-4, density: 1000}
meshes:
  cable:
    generator: {type: cable_chain, points: [[0, 0, 0], [1, 0, 0]], divisions: [10]}
    cable_material: rope
constraints:
  - {nodes: [cable/start, cable/end], fix: all}
  - {nodes: cable, fix: [y, z]}
time: {end: 1, fixed_dt: 9.0e-5}
)";

// One cable element from a fixed node to node B at x = 1 m, B moving along x only: a linear spring-mass
// oscillator, m = ρ A L / 2 = 0.05 kg, k = EA/L = 1e5 N/m (ω = 1414 rad/s).
const char* kOscillator = R"(materials:
  rope: {type: cable, young: 1.0e9, area: 1.0e-4, density: 1000}
meshes:
  cable:
    generator: {type: cable_chain, points: [[0, 0, 0], [1, 0, 0]], divisions: [1]}
    cable_material: rope
constraints:
  - {nodes: cable/start, fix: all}
  - {nodes: cable/end, fix: [y, z]}
time: {end: 1, fixed_dt: 1.0e-6}
)";

struct Integration {
  Scene scene;
  std::unique_ptr<CentralDifference> cd;
  explicit Integration(const std::string& yaml, const std::vector<std::string>& sets = {})
      : scene(loadSceneFromString(yaml, "ledger.yaml", sets)) {
    cd = std::make_unique<CentralDifference>(*scene.model, scene.effectList(), scene.constraints,
                                             scene.time.integrator);
  }
  Nodes& nodes() { return scene.model->nodes; }
  double mass(int node) { return scene.model->nodes.mass[node]; }
  int node(const std::string& group) {
    const auto& m = scene.model->meshes[0];
    return m.node[m.source.nodeGroups.at(group)[0]];
  }
};

}  // namespace

// The leapfrog conserves ½ v(n−½)·M v(n+½) + U(x(n)) exactly for an undamped linear system. Both terms are
// computed here from the velocities and the element energy, not taken from the ledger; the ledger's balance
// is round-off at every step, while the physical energy (mid-step velocity) is off at O(Δt²).
TEST(EnergyLedger, UndampedLinearChainKeepsTheModifiedEnergyExactlyAtEveryStep) {
  Integration it(kChain);
  Nodes& N = it.nodes();
  for (int i = 0; i < N.count; ++i) {
    N.x[3 * i] = 1.01 * N.X[3 * i];  // taut throughout: 1 % pre-stretch, axial velocities well below that
    N.v[3 * i] = 0.5 * std::sin(M_PI * N.X[3 * i]) + 0.2 * std::sin(7 * M_PI * N.X[3 * i]);
  }
  it.cd = std::make_unique<CentralDifference>(*it.scene.model, it.scene.effectList(), it.scene.constraints,
                                              it.scene.time.integrator);
  const std::vector<double> v0 = N.v;
  std::vector<double> vPrev = N.v;
  double e0 = 0, worstModified = 0, worstBalance = 0, worstPhysical = 0;
  for (int n = 0; n < 3000; ++n) {
    ASSERT_TRUE(it.cd->step(1e9, true));
    const EnergyLedger& E = it.cd->energy();
    // Product-form kinetic energy at step n from the two half-step velocities around it; at n = 0 the
    // virtual v(−½) = 2 v(0) − v(½) of the half-step start.
    double kx = 0, kProduct = 0, kPhys = 0;
    for (int d = 0; d < 3 * N.count; ++d) {
      const double before = n == 0 ? 2 * v0[d] - N.v[d] : vPrev[d];
      kx += 0.5 * it.mass(d / 3) * before * N.v[d];
      kProduct += 0.5 * it.mass(d / 3) * vPrev[d] * N.v[d];
      kPhys += 0.5 * it.mass(d / 3) * std::pow(0.5 * (vPrev[d] + N.v[d]), 2);
    }
    const double modified = kx + E.strain;  // E.strain: the elements' energy at x(n), evaluated by the step
    if (n == 0) e0 = modified;
    worstModified = std::max(worstModified, std::abs(modified - e0) / e0);
    worstBalance = std::max(worstBalance, E.balanceError());
    if (n > 0) worstPhysical = std::max(worstPhysical, std::abs(kPhys + E.strain - e0) / e0);
    EXPECT_NEAR(E.kineticProduct, kProduct, 1e-12 * e0) << "step " << n;
    vPrev = N.v;
  }
  EXPECT_LT(worstModified, 1e-12);
  EXPECT_LT(worstBalance, 1e-12);
  EXPECT_GT(worstPhysical,
            1e-4);  // the physical energy is not conserved exactly: the check above is not void
}

// A constant force F on the oscillator's free node, mass damping α, released at rest at the spring's rest
// length: m ÿ = −k y − α m ẏ about the equilibrium y* = F/k. Independent expectations: the work of a constant
// force is F·(x(n) − x(0)) (trapezoidal, exact), and the dissipation of the continuous damped oscillator is
// D(t) = E(0) − E(t), E = ½ m ẏ² + ½ k y², from its closed-form solution (to O(Δt²)).
TEST(EnergyLedger, DampedOscillatorBooksTheForceWorkAndTheDissipationOfTheAnalyticalSolution) {
  const double F = 100, alpha = 200;
  Integration it(std::string(kOscillator) +
                 "effects:\n  nodal_forces: {nodes: cable/end, force: [100, 0, 0]}\n"
                 "  mass_damping: {alpha: 200}\n");
  Nodes& N = it.nodes();
  const int b = it.node("end");
  const double m = it.mass(b), k = 1e9 * 1e-4 / 1.0;
  ASSERT_NEAR(m, 0.05, 1e-15);
  const double w = std::sqrt(k / m), zeta = alpha / (2 * w), wd = w * std::sqrt(1 - zeta * zeta);
  const double y0 = -F / k, e0 = 0.5 * k * y0 * y0;
  auto energy = [&](double t) {  // E(t) of the continuous damped oscillator
    const double c = std::cos(wd * t), s = std::sin(wd * t), decay = std::exp(-zeta * w * t);
    const double y = decay * (y0 * c + zeta * w * y0 / wd * s);
    const double yd =
        decay * (-zeta * w * (y0 * c + zeta * w * y0 / wd * s) + (-y0 * wd * s + zeta * w * y0 * c));
    return 0.5 * m * yd * yd + 0.5 * k * y * y;
  };
  const double x0 = N.x[3 * b];
  double worstWork = 0, worstBalance = 0, worstDissipation = 0;
  for (int n = 0; n < 10000; ++n) {  // 10 ms, about two periods, dissipating 87 % of the energy
    const double xn = N.x[3 * b], tn = it.cd->time();  // the state the step evaluates its forces at
    ASSERT_TRUE(it.cd->step(1e9, false));
    const EnergyLedger& E = it.cd->energy();  // energies at step n, work through x(n)
    worstBalance = std::max(worstBalance, E.balanceError());
    if (n == 0) continue;  // step 0 splits the first half step by convention (EnergyLedger.hpp)
    worstWork = std::max(worstWork, std::abs(E.externalWork - F * (xn - x0)) / e0);
    worstDissipation = std::max(worstDissipation, std::abs(E.massDamping - (e0 - energy(tn))) / e0);
  }
  // F·(x(n) − x(0)) carries the round-off of 10⁴ position updates of a coordinate near 1 m (~1e-12 m),
  // the ledger only that of its sums.
  EXPECT_LT(worstWork, 1e-9);
  EXPECT_LT(worstBalance, 1e-12);
  EXPECT_LT(worstDissipation, 1e-4) << "ω Δt = " << w * 1e-6;
  EXPECT_GT(it.cd->energy().massDamping, 0.8 * e0);  // most of the energy is gone: the test is not void
}

// A rigid pair pushed by a constant force on each node (the cable between them keeps its length): leapfrog
// with the half-step start integrates a constant acceleration exactly, so the booked work equals the work of
// the continuous solution, F·a·t², at every step.
TEST(EnergyLedger, ConstantForceOnAFreeBodyBooksTheAnalyticalWork) {
  Integration it(R"(materials:
  rope: {type: cable, young: 1.0e9, area: 1.0e-4, density: 1000}
meshes:
  cable:
    generator: {type: cable_chain, points: [[0, 0, 0], [1, 0, 0]], divisions: [1]}
    cable_material: rope
effects:
  nodal_forces: {nodes: cable, force: [2, 1, -3]}
time: {end: 1, fixed_dt: 1.0e-3}
)");
  const double m = it.mass(0);  // each node: ρ A L / 2
  const double f2 = 4 + 1 + 9, a2 = f2 / (m * m);
  double worst = 0;
  for (int n = 0; n < 500; ++n) {
    const double tn = it.cd->time();
    ASSERT_TRUE(it.cd->step(1e9, false));
    EXPECT_LT(it.cd->energy().balanceError(), 1e-13) << "step " << n;
    if (n == 0) continue;  // step 0 splits the first half step by convention (EnergyLedger.hpp)
    const double exact = 2 * std::sqrt(f2) * 0.5 * std::sqrt(a2) * tn * tn;  // 2 nodes · F · ½ a t²
    worst = std::max(worst, std::abs(it.cd->energy().externalWork - exact) / exact);
  }
  EXPECT_LT(worst, 1e-12);
}

// The free end of the oscillator driven at a constant velocity V (no free dof left): the support supplies the
// node's kinetic energy ½ m V² at the start (an impulse) and then the spring's energy ½ k (V t)², exactly, at
// any step size. The old bookkeeping missed the first and booked the second one-sided.
TEST(EnergyLedger, PrescribedVelocityBooksTheSupportWorkAtEveryStepSize) {
  const double V = 0.5;
  for (const char* dt : {"1.0e-4", "1.0e-5", "1.0e-6"}) {
    Integration it(replaceOnce(kOscillator, "  - {nodes: cable/end, fix: [y, z]}",
                               "  - {nodes: cable/end, fix: [y, z]}\n"
                               "  - {nodes: cable/end, prescribe: {component: x, amplitude: 0.01, function: "
                               "{type: ramp, duration: 0.02}}}"),
                   {std::string("time.fixed_dt=") + dt});
    const int b = it.node("end");
    const double m = it.mass(b), k = 1e5;
    const int steps = int(std::lround(0.01 / std::stod(dt)));  // half the ramp
    for (int n = 0; n < steps; ++n) {
      const double tn = it.cd->time();
      ASSERT_TRUE(it.cd->step(1e9, true));
      const EnergyLedger& E = it.cd->energy();
      ASSERT_LT(E.balanceError(), 1e-12) << "dt " << dt << ", step " << n;
      if (n == 0) continue;  // the impulse that sets the node moving acts between step 0 and step 1
      // The velocity the support imposes, (x(n+1) − x(n))/Δt with x near 1 m, carries ulp(1 m)/Δt of
      // round-off: up to 4e-10 relative at Δt = 1e-6 s.
      const double exact = 0.5 * m * V * V + 0.5 * k * (V * tn) * (V * tn);
      ASSERT_NEAR(E.externalWork, exact, 1e-8 * exact) << "dt " << dt << ", step " << n;
    }
  }
}

// A membrane strip stretched by one edge moving at a prescribed velocity, through `fsi run`'s loop with the
// energy checked at every step: the balance is round-off and the run ends normally whatever the step (the
// old bookkeeping stopped it as unstable at max_dt 1e-6, error 0.55, because the support's inertial work
// was not booked).
TEST(EnergyLedger, PrescribedEdgeMotionRunIsStableAtEveryStep) {
  const char* strip = R"(materials:
  film: {type: membrane, young: 1.0e8, poisson: 0.3, thickness: 1.0e-3, density: 1000}
meshes:
  strip:
    generator: {type: rectangle, size: [1, 0.2], divisions: [20, 4]}
    material: film
constraints:
  - {nodes: strip/xmin, fix: all}
  - {nodes: strip/xmax, prescribe: {component: x, amplitude: 0.01, function: {type: ramp, duration: 0.02}}}
  - {nodes: strip/xmax, fix: [y, z]}
  - {nodes: strip, fix: z}
time: {end: 0.004, monitor_every: 1}
output: {interval: 0}
probes:
  reaction: {type: reaction, nodes: strip/xmax, component: x}
)";
  for (const char* maxDt : {"1.0e-4", "1.0e-5", "1.0e-6"}) {
    Scene s = loadSceneFromString(strip, "strip.yaml", {std::string("time.max_dt=") + maxDt});
    RunOptions opt;
    opt.outDir = outDir(std::string("ledger-strip-") + maxDt);
    opt.quiet = true;
    const RunResult r = runSimulation(s, opt);
    EXPECT_EQ(r.reason, StopReason::EndTime) << maxDt << ": " << r.diagnosis;
    EXPECT_LT(r.summary["stats"]["energy_balance_error"].get<double>(), 1e-12) << maxDt;
    EXPECT_GT(r.summary["stats"]["external_work"].get<double>(), 0.0) << maxDt;
  }
}

// A chain hanging from a fixed point whose other end slides on an oblique plane (normal (1, 1, 0)/√2) under
// gravity: the plane's reaction does no work, and removing the normal velocity is booked, so the balance
// stays round-off at every step.
TEST(EnergyLedger, SlidingPlaneKeepsTheBalanceExact) {
  Integration it(R"(materials:
  rope: {type: cable, young: 1.0e7, area: 1.0e-4, density: 1000}
meshes:
  cable:
    generator: {type: cable_chain, points: [[0, 0, 0], [1, 1, 0]], divisions: [8]}
    cable_material: rope
constraints:
  - {nodes: cable/start, fix: all}
  - {symmetry: {point: [1, 1, 0], normal: [1, 1, 0]}}
effects:
  gravity: {acceleration: [0, 0, -9.8]}
  mass_damping: {alpha: 2}
time: {end: 1}
)");
  ASSERT_EQ(it.scene.constraints.sliders.size(), 1u);
  for (int n = 0; n < 20000; ++n) {
    ASSERT_TRUE(it.cd->step(1e9, n % 10 == 0));
    ASSERT_LT(it.cd->energy().balanceError(), 1e-12) << "step " << n;
  }
  const Nodes& N = it.nodes();
  const int e = it.node("end");
  EXPECT_NEAR(N.x[3 * e] + N.x[3 * e + 1], 2.0, 1e-12);  // still on the plane
  EXPECT_LT(N.x[3 * e + 2], -0.01);                      // and it moved: the check is not void
}

// Checking the energy at every step used to stop these scenes at step 1 ("unstable", error 1): the
// half-step kinetic energy had no work booked yet. The exact bookkeeping has none to miss.
TEST(EnergyLedger, MonitoringEveryStepRaisesNoFalseAlarm) {
  for (const auto& [scene, maxTime] : {std::pair{"hencky", "0.004"}, std::pair{"sphere", "0.002"},
                                       std::pair{"airbag", "0.01"}, std::pair{"catenary-cable", "0.02"}}) {
    Scene s = loadScene(
        fs::path(FSI_SOURCE_DIR) / "cases/structure" / scene / "scene.yaml",
        {"time.monitor_every=1", std::string("time.until_static.max_time=") + maxTime, "output.interval=0"});
    RunOptions opt;
    opt.outDir = outDir(std::string("ledger-monitor1-") + scene);
    opt.quiet = true;
    const RunResult r = runSimulation(s, opt);
    EXPECT_NE(r.reason, StopReason::Unstable) << scene << ": " << r.diagnosis;
    EXPECT_GT(r.summary["stats"]["steps"].get<long>(), 100) << scene;
    EXPECT_LT(r.summary["stats"]["energy_balance_error"].get<double>(), 1e-12) << scene;
    // The largest step-to-step velocity energy is the start's (1/8 of the supplied energy from rest).
    EXPECT_LE(r.summary["stats"]["energy_growth_max"].get<double>(), 0.125 + 1e-9) << scene;
  }
}
