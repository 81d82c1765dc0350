// Hard cases for cables (ctest label `hard`): a cable net that goes slack and snaps taut again, and a cable
// pendulum swinging through large angles (a mechanism: no stiffness against the swing).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "HardCases.hpp"
#include "structure/integrate/CentralDifference.hpp"

using namespace fsi::structure;
using fsi::test::expectStableRun;
using fsi::test::finiteState;
using fsi::test::groupNodes;
using fsi::test::runHard;
namespace fs = std::filesystem;

namespace {

constexpr double kG = 9.81;

// A cross-shaped net: four arms of `segments` cables each from a centre node to anchors at (±a, 0, 0) and
// (0, ±a, 0), the centre raised by h0 in the reference geometry (a pyramid), written as an MSH 2.2 file with
// the node groups `anchors` and `center` and the line group `net`.
void writeCrossNet(const fs::path& file, double a, double h0, int segments) {
  std::vector<std::array<double, 3>> p{{0, 0, h0}};
  std::vector<std::array<int, 2>> lines;
  const double dir[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  std::vector<int> anchors;
  for (const auto& d : dir) {
    int prev = 0;
    for (int k = 1; k <= segments; ++k) {
      const double s = double(k) / segments;
      p.push_back({s * a * d[0], s * a * d[1], (1 - s) * h0});
      lines.push_back({prev, int(p.size()) - 1});
      prev = int(p.size()) - 1;
    }
    anchors.push_back(prev);
  }
  std::ofstream out(file);
  out.precision(17);
  out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n3\n0 1 \"anchors\"\n0 2 \"center\"\n"
         "1 3 \"net\"\n$EndPhysicalNames\n$Nodes\n"
      << p.size() << "\n";
  for (std::size_t i = 0; i < p.size(); ++i)
    out << i + 1 << " " << p[i][0] << " " << p[i][1] << " " << p[i][2] << "\n";
  out << "$EndNodes\n$Elements\n" << anchors.size() + 1 + lines.size() << "\n";
  int id = 1;
  for (int n : anchors) out << id++ << " 15 2 1 1 " << n + 1 << "\n";
  out << id++ << " 15 2 2 2 1\n";
  for (const auto& l : lines) out << id++ << " 1 2 3 3 " << l[0] + 1 << " " << l[1] + 1 << "\n";
  out << "$EndElements\n";
}

// The static depth of the cross under a load P at its centre: each arm is straight with tension EAε, length
// ℓ(1 + ε) = √(a² + d²), and the four arms carry P: 4 EA ε d/(ℓ(1 + ε)) = P. Bisection on ε.
double crossDepth(double a, double ell, double EA, double P) {
  auto depth = [&](double eps) {
    return std::sqrt(std::max(0.0, ell * ell * (1 + eps) * (1 + eps) - a * a));
  };
  double lo = 0, hi = 1;
  for (int i = 0; i < 200; ++i) {
    const double eps = 0.5 * (lo + hi);
    (4 * EA * eps * depth(eps) / (ell * (1 + eps)) < P ? lo : hi) = eps;
  }
  return depth(0.5 * (lo + hi));
}

}  // namespace

// A cross-shaped cable net whose arms are 2 % longer than their span: started flat, every cable is slack. A
// 100 N load at the centre (on a 0.1 kg point mass) at once: the centre falls until the arms snap taut,
// rebounds, settles; at 0.6 s the load turns upward (the net goes slack again and snaps taut on the other
// side), at 1.0 s it turns down again (a third snap). After each reversal the centre flies 0.5 m through the
// slack range at up to 12.5 m/s (the terminal speed under the mass damping) and the tension peaks at 1.8
// times its static value. Stable means: each snap leaves the bookkeeping bounded (the run's checks pass, the
// elements create < 0.1 % of the energy supplied) and after each re-tensioning the net settles on the static
// answer of the straight arms (crossDepth, independent of the code), the centre at −d after the first and the
// last snap and at +d while the load pulls up.
TEST(HardCable, NetGoingSlackAndSnappingTautReturnsToItsStaticState) {
  const double a = 1.0, h0 = 0.2, E = 1.0e9, A = 1.0e-5, P = 100;
  const fs::path dir = fsi::test::outDir("hard-cable-net-mesh");
  fs::create_directories(dir);
  writeCrossNet(dir / "net.msh", a, h0, 4);
  const std::string yaml = R"(materials:
  line: {type: cable, young: 1.0e9, area: 1.0e-5, density: 1000}
  bob: {type: point_mass, mass: 0.1}
meshes:
  net: {file: net.msh, cable_material: line, cables: all, point_masses: {center: bob}}
constraints:
  - {nodes: net/anchors, fix: all}
effects:
  nodal_forces: {nodes: net/center, force: [0, 0, -100],
                 function: {type: table, points: [[0, 1], [0.6, 1], [0.6001, -1], [1.0, -1], [1.0001, 1]]}}
  mass_damping: {alpha: 80}
  bulk_viscosity: {b1: 0.06}
time: {end: 1.6}
probes:
  center_z: {type: position, nodes: net/center, component: z}
  tension: {type: line_tension, lines: net, reduce: min}
)";
  const double d = crossDepth(a, std::sqrt(a * a + h0 * h0), E * A, P);
  for (const auto& [end, expected] : {std::pair{0.6, -d}, std::pair{1.0, d}, std::pair{1.6, -d}}) {
    Scene s = loadSceneFromString(yaml, (dir / "net.yaml").string(), {"time.end=" + std::to_string(end)});
    Nodes& N = s.model->nodes;
    for (int i = 0; i < N.count; ++i) N.x[3 * i + 2] = 0;  // flat start: every arm 2 % too long, slack
    const RunResult r = runHard(s, "cable-net-" + std::to_string(end));
    expectStableRun(r, s);
    EXPECT_NEAR(r.probes.at("center_z"), expected, 1e-4 * d) << "t = " << end;
    EXPECT_GT(r.probes.at("tension"), 0.9 * P / 4) << "every cable taut again at t = " << end;
    EXPECT_LT(r.summary["stats"]["kinetic_energy"].get<double>(), 1e-9 * P * d) << "at rest at t = " << end;
    std::printf("cable net at t = %g: centre %.7g m (exact %.7g), energy created %.2e, growth %.2e\n", end,
                r.probes.at("center_z"), expected, r.summary["stats"]["energy_created_max"].get<double>(),
                r.summary["stats"]["energy_growth_max"].get<double>());
  }
}

// A cable pendulum released horizontally (θ0 = 90°): one stiff, light cable, a 1 kg bob, no damping. A
// mechanism swinging through 180°, with the cable's tension starting from zero. The exact period of the rigid
// pendulum is 4√(L/g) K(sin(θ0/2)) (complete elliptic integral; the large-amplitude series 2π√(L/g)(1 +
// θ0²/16
// + 11θ0⁴/3072 + 173θ0⁶/737280 + ...) converges to it, 18 % above the small-angle period). Stable means: the
// period within 1e-4 of it (the cable stretches by Mg·3/EA = 1.5e-5 at the bottom), the total energy kinetic
// + strain + potential conserved to 1e-5 of MgL over three periods (central differences conserve it to
// O(Δt²)), and the bob's distance from the pivot never off L by more than the stretch allows.
TEST(HardCable, LargeAmplitudePendulumKeepsItsPeriodAndEnergy) {
  const double L = 1.0, M = 1.0, E = 2.0e9, A = 1.0e-3, rho = 10;
  const std::string yaml = R"(materials:
  line: {type: cable, young: 2.0e9, area: 1.0e-3, density: 10}
  bob: {type: point_mass, mass: 1}
meshes:
  pendulum:
    generator: {type: cable_chain, points: [[0, 0, 0], [1, 0, 0]], divisions: [1]}
    cable_material: line
    point_masses: {end: bob}
constraints:
  - {nodes: pendulum/start, fix: all}
effects:
  gravity: {acceleration: [0, 0, -9.81]}
time: {end: 10}
)";
  Scene s = loadSceneFromString(yaml, "pendulum.yaml");
  Model& m = *s.model;
  const int bob = groupNodes(m, "end")[0];
  const double bobMass = m.nodes.physicalMass[bob];
  EXPECT_NEAR(bobMass, M + 0.5 * rho * A * L, 1e-12);
  CentralDifference cd(m, s.effectList(), s.constraints, s.time.integrator);
  std::vector<double> crossings;  // downward zero crossings of x (from x > 0 to x ≤ 0), interpolated in time
  double tPrev = 0, xPrev = m.nodes.x[3 * bob], worstEnergy = 0, worstLength = 0;
  long step = 0;
  while (crossings.size() < 4) {
    const bool monitor = ++step % 50 == 0;
    ASSERT_TRUE(cd.step(20.0, monitor));
    const double t = cd.time(), x = m.nodes.x[3 * bob], z = m.nodes.x[3 * bob + 2];
    if (xPrev > 0 && x <= 0) crossings.push_back(tPrev + (t - tPrev) * xPrev / (xPrev - x));
    tPrev = t, xPrev = x;
    worstLength = std::max(worstLength, std::abs(std::hypot(x, z) - L));
    if (monitor) {  // kinetic + strain + potential (−work of gravity) against the start, where all three are
                    // 0
      const EnergyLedger& e = cd.energy();
      worstEnergy =
          std::max(worstEnergy, std::abs(e.kinetic + e.strain - e.externalWork) / (bobMass * kG * L));
    }
    ASSERT_LT(t, 19.0);
  }
  const double period = (crossings.back() - crossings.front()) / double(crossings.size() - 1);
  const double exact = 4 * std::sqrt(L / kG) * std::comp_ellint_1(std::sin(M_PI / 4));
  const double th = M_PI / 2, th2 = th * th;
  const double series =
      2 * M_PI * std::sqrt(L / kG) * (1 + th2 / 16 + 11 * th2 * th2 / 3072 + 173 * th2 * th2 * th2 / 737280);
  EXPECT_NEAR(period / exact - 1, 0.0, 1e-4) << "period " << period << " s, exact " << exact << " s";
  EXPECT_NEAR(series / exact - 1, 0.0, 2e-3) << "the series to θ0⁶ is within its next term";
  std::printf(
      "pendulum: period %.8g s, exact %.8g s (%.2e), series to theta^6 %.8g s, energy %.2e, length "
      "%.2e m, %ld steps\n",
      period, exact, period / exact - 1, series, worstEnergy, worstLength, cd.steps());
  EXPECT_LT(worstEnergy, 1e-5);
  EXPECT_LT(worstLength, 3 * bobMass * kG * L / (E * A) * 1.5);
  EXPECT_LT(cd.energy().maxGrowth, 4.3);
  EXPECT_TRUE(finiteState(m));
}
