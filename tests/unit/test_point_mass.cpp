// The point-mass element kind (a payload): its mass joins the lumped mass, gravity acts on it, it adds no
// force and does not bound the step; scenes attach it to a node group (`point_masses:`), with located errors.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "TestScenes.hpp"
#include "structure/elements/CableForces.hpp"
#include "structure/elements/ElementKind.hpp"
#include "structure/elements/PointMassElement.hpp"
#include "structure/integrate/CentralDifference.hpp"
#include "structure/integrate/MassScaling.hpp"
#include "structure/model/Error.hpp"
#include "structure/run/Simulation.hpp"
#include "structure/scene/Scene.hpp"

using namespace fsi::structure;

namespace {

constexpr double kG = 9.81;

// A 2 m line of 8 cables hanging from its fixed top end, a payload of 80 kg at the bottom.
const char* kHanging = R"(materials:
  line: {type: cable, young: 4.3e10, area: 3.0e-6, density: 906}
  payload: {type: point_mass, mass: 80}
meshes:
  riser:
    generator: {type: cable_chain, points: [[0, 0, 0], [0, 0, -2]], divisions: [8]}
    cable_material: line
    point_masses: {end: payload}
constraints:
  - {nodes: riser/start, fix: all}
effects:
  gravity: {acceleration: [0, 0, -9.81]}
solver: {type: dynamic_relaxation, tolerance: 1.0e-10}
)";

std::string errorOf(const std::string& yaml) {
  return fsi::test::sceneError(yaml, "payload.yaml");
}

using fsi::test::replaced;

}  // namespace

TEST(PointMass, IsARegisteredKindWithoutForcesOrStepBound) {
  const ElementKind* kind = findElementKind("point_mass");
  ASSERT_NE(kind, nullptr);
  Scene s = loadSceneFromString(kHanging, "payload.yaml");
  const Model& m = *s.model;
  ASSERT_EQ(kind->count(m), 1);
  EXPECT_EQ(kind->describe(m, 0), "point mass 1 of mesh 'riser'");
  EXPECT_EQ(kind->makeForces(m, ElementDamping{}), nullptr);
  EXPECT_TRUE(std::isinf(kind->referenceStableDt(m)));
  // The whole model's step is the cables' own: L_e / c with c = sqrt(E/ρ).
  EXPECT_DOUBLE_EQ(referenceStableDt(m), 0.25 * std::sqrt(906 / 4.3e10));
  // Only the cables' force effect is built for the elements.
  for (const std::string& e : s.enabledEffects) EXPECT_NE(e, "point_mass");
}

TEST(PointMass, AddsItsMassToTheNodeAndGravityActsOnIt) {
  Scene s = loadSceneFromString(kHanging, "payload.yaml");
  const Model& m = *s.model;
  const int node = pointMassesOf(m).node[0];
  const double halfCable = 0.5 * 906 * 3.0e-6 * 0.25;
  EXPECT_NEAR(m.nodes.physicalMass[node], 80 + halfCable, 1e-12);
  double total = 0;
  for (double mi : m.nodes.physicalMass) total += mi;
  EXPECT_NEAR(total, 80 + 906 * 3.0e-6 * 2.0, 1e-12);
}

// Static state by dynamic relaxation: each cable carries the weight of everything below its upper node —
// the bottom one the payload plus half an element of line, the top one the payload plus the line less the
// half element lumped at the fixed top node (equilibrium of the lumped chain, independent of the solver). The
// relaxation stops at a relative residual of 1e-10, hence the tolerance 1e-9.
TEST(PointMass, HangingPayloadTensionIsItsWeightPlusTheLineBelow) {
  Scene s = loadSceneFromString(kHanging, "payload.yaml");
  RunOptions opt;
  opt.outDir = fsi::test::outDir("point-mass-hanging");
  opt.quiet = true;
  const RunResult r = runSimulation(s, opt);
  ASSERT_EQ(r.reason, StopReason::Static) << r.diagnosis;
  const Model& m = *s.model;
  std::vector<double> T;
  cableTensions(m.cables, m.nodes.x.data(), T);
  const double rhoA = 906 * 3.0e-6, Le = 0.25;
  const int bottom = pointMassesOf(m).node[0];
  for (int e = 0; e < m.cables.count; ++e) {
    const int a = m.cables.conn[2 * e], b = m.cables.conn[2 * e + 1];
    // Cable elements below: count the nodes strictly below this element's upper node (z of the reference).
    const double zUpper = std::max(m.nodes.X[3 * a + 2], m.nodes.X[3 * b + 2]);
    const int below = int(std::lround(-zUpper / Le));  // element index from the top, 0..7
    const double expected = kG * (80 + rhoA * Le * (8 - below - 0.5));
    EXPECT_NEAR(T[e], expected, 1e-9 * expected) << "cable " << e;
    if (a == bottom || b == bottom) {
      EXPECT_NEAR(T[e], kG * (80 + 0.5 * rhoA * Le), 1e-9 * T[e]);
    }
  }
}

// A pendulum: one stiff, light cable of length L, a heavy point mass, released from rest at θ0 = 0.05. The
// reference is the simple pendulum's period 2π√(L/g) with its known finite-amplitude series
// (1 + θ0²/16 + 11θ0⁴/3072) and the length the payload's weight stretches the cable to, L(1 + Mg/EA). The
// lumped line mass sits on the pivot and on the bob, which does not change a simple pendulum's period. What
// is left is discretisation: the central-difference phase error (ω dt)²/24 ≈ 1e-10, and the axial ripple of
// the bob (the cable starts unstretched: amplitude ≈ Mg/EA·L ≈ 1e-5 m, sin θ0 of it in x) that shifts each
// zero crossing of x by at most 1e-5·0.05/(θ0 ω L) ≈ 3e-6 s, 1.6e-6 of a period. Tolerance 5e-6 relative.
TEST(PointMass, PendulumSmallOscillationPeriod) {
  const double L = 1.0, M = 10.0, theta0 = 0.05, E = 1e12, A = 1e-5, rho = 1000;
  std::ostringstream end;
  end.precision(17);
  end << "[" << L * std::sin(theta0) << ", 0, " << -L * std::cos(theta0) << "]";
  const std::string yaml = R"(materials:
  line: {type: cable, young: 1.0e12, area: 1.0e-5, density: 1000}
  bob: {type: point_mass, mass: 10}
meshes:
  pendulum:
    generator: {type: cable_chain, points: [[0, 0, 0], )" +
                           end.str() +
                           R"(], divisions: [1]}
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
  const int bob = pointMassesOf(m).node[0];
  CentralDifference cd(m, s.effectList(), s.constraints, CentralDifferenceSettings{});
  // Upward zero crossings of x (from x < 0 to x ≥ 0), linearly interpolated in time.
  std::vector<double> crossings;
  double tPrev = 0, xPrev = m.nodes.x[3 * bob];
  while (crossings.size() < 4) {
    ASSERT_TRUE(cd.step(20.0, false));
    const double t = cd.time(), x = m.nodes.x[3 * bob];
    if (xPrev < 0 && x >= 0) crossings.push_back(tPrev + (t - tPrev) * (-xPrev) / (x - xPrev));
    tPrev = t, xPrev = x;
    ASSERT_LT(t, 19.0);
  }
  const double period = (crossings.back() - crossings.front()) / double(crossings.size() - 1);
  const double bobMass = M + 0.5 * rho * A * L;
  const double stretched = L * (1 + bobMass * kG / (E * A));
  const double th2 = theta0 * theta0;
  const double reference = 2 * M_PI * std::sqrt(stretched / kG) * (1 + th2 / 16 + 11 * th2 * th2 / 3072);
  EXPECT_NEAR(period / reference - 1, 0.0, 5e-6) << "period " << period << " s, reference " << reference
                                                 << " s, 2π√(L/g) = " << 2 * M_PI * std::sqrt(L / kG);
}

TEST(PointMass, ParafoilPayloadNodeCarriesTheMassAndItsShareOfTheRiser) {
  const char* yaml = R"(materials:
  fabric: {type: membrane, young: 1.3e9, poisson: 0.3, thickness: 7.6e-5, density: 530}
  line: {type: cable, young: 4.3e10, area: 3.0e-6, density: 906}
  payload: {type: point_mass, mass: 80}
meshes:
  wing:
    generator: {type: parafoil, cells: 4, chordwise_points: 12, span_divisions: 1, section: NACA 2412,
                intake: {from: 0.0, to: 0.05}, riser_length: 0.4, brake_points: 2}
    material: fabric
    cable_material: line
    point_masses: {payload: payload}
constraints:
  - {nodes: wing/confluence, fix: all}
time: {end: 1.0e-3}
)";
  Scene s = loadSceneFromString(yaml, "parafoil.yaml");
  const Model& m = *s.model;
  const MeshData& src = m.meshes[0].source;
  ASSERT_EQ(src.nodeGroups.at("payload").size(), 1u);
  const int local = src.nodeGroups.at("payload")[0];
  // Its share of line mass, from the generated mesh: half of every line that ends at the payload node.
  double share = 0;
  for (const auto& l : src.lines)
    if (l[0] == local || l[1] == local) {
      double len2 = 0;
      for (int k = 0; k < 3; ++k) len2 += std::pow(src.points[l[1]][k] - src.points[l[0]][k], 2);
      share += 0.5 * 906 * 3.0e-6 * std::sqrt(len2);
    }
  EXPECT_GT(share, 0);
  ASSERT_EQ(pointMassesOf(m).count, 1);
  EXPECT_EQ(pointMassesOf(m).node[0], m.meshes[0].node[local]);
  EXPECT_NEAR(m.nodes.physicalMass[m.meshes[0].node[local]], 80 + share, 1e-12);
}

TEST(PointMass, BadMassAndMisspeltKeysAreLocated) {
  for (const char* bad : {"0", "-3", ".nan", ".inf", "1.0e-320"}) {
    const std::string e = errorOf(replaced(kHanging, "mass: 80", std::string("mass: ") + bad));
    EXPECT_NE(e.find("payload.yaml:3"), std::string::npos) << bad << ": " << e;
    EXPECT_NE(e.find("mass"), std::string::npos) << e;
  }
  const std::string typo = errorOf(replaced(kHanging, "mass: 80", "mas: 80"));
  EXPECT_NE(typo.find("payload.yaml:3"), std::string::npos) << typo;
  EXPECT_NE(typo.find("mass"), std::string::npos) << typo;
  const std::string group = errorOf(replaced(kHanging, "{end: payload}", "{ends: payload}"));
  EXPECT_NE(group.find("payload.yaml:8"), std::string::npos) << group;
  EXPECT_NE(group.find("did you mean 'end'"), std::string::npos) << group;
  const std::string material = errorOf(replaced(kHanging, "{end: payload}", "{end: payloda}"));
  EXPECT_NE(material.find("payload.yaml:8"), std::string::npos) << material;
  EXPECT_NE(material.find("did you mean 'payload'"), std::string::npos) << material;
  const std::string key = errorOf(replaced(kHanging, "point_masses:", "point_mass:"));
  EXPECT_NE(key.find("payload.yaml:8"), std::string::npos) << key;
  EXPECT_NE(key.find("point_masses"), std::string::npos) << key;
  // A cable material is not a point-mass material.
  const std::string kind = errorOf(replaced(kHanging, "{end: payload}", "{end: line}"));
  EXPECT_NE(kind.find("no point_mass material named 'line'"), std::string::npos) << kind;
}
