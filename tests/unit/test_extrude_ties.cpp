// The `extrude` constraint: a strip one element wide along an extrusion direction as a 2D model. The nodes
// at equal coordinates across the direction (the rows of the strip) form tie groups that move as one. Checked
// against references independent of the tie's code: rows identical at every step, momentum conservation of
// a free strip, the leapfrog's conserved energy of a linear-in-time system, the discrete string's closed-form
// deflection, and the located errors of bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "TestScenes.hpp"
#include "structure/integrate/CentralDifference.hpp"
#include "structure/integrate/DynamicRelaxation.hpp"
#include "structure/scene/Scene.hpp"

using namespace fsi::structure;
using fsi::test::replaced;
using fsi::test::sceneError;

namespace {

// A strip 1 m long, 0.05 m wide (y, the extrusion), 20 squares along x and one across, ruled (each square
// cut along one diagonal: the triangulation is not symmetric between the rows).
std::string stripScene(const std::string& constraints, const std::string& extra = "time: {end: 1}\n") {
  return std::string(R"(materials:
  film: {type: membrane, young: 1.0e6, poisson: 0.3, thickness: 1.0e-3, density: 1000}
meshes:
  strip:
    generator: {type: rectangle, size: [1, 0.05], divisions: [20, 1], center: [0.5, 0.025, 0]}
    material: film
constraints:
)") + constraints +
         extra;
}

const char* kTie = "  - {nodes: strip, extrude: {direction: [0, 1, 0]}}\n";
const char* kTieHold = "  - {nodes: strip, extrude: {direction: [0, 1, 0], hold: true}}\n";

// The strip's node pairs (row y = 0, row y = w) by x, from the reference coordinates.
std::vector<std::pair<int, int>> rows(const Nodes& N) {
  std::map<double, std::vector<int>> byX;
  for (int i = 0; i < N.count; ++i) byX[N.X[3 * i]].push_back(i);
  std::vector<std::pair<int, int>> pairs;
  for (auto& [x, nodes] : byX) {
    EXPECT_EQ(nodes.size(), 2u) << x;
    std::sort(nodes.begin(), nodes.end(), [&](int a, int b) { return N.X[3 * a + 1] < N.X[3 * b + 1]; });
    pairs.push_back({nodes[0], nodes[1]});
  }
  return pairs;
}

// Largest difference between the rows' displacement components `comps` (x = 0, z = 2).
double rowDifference(const Nodes& N, const std::vector<std::pair<int, int>>& pairs, std::vector<int> comps) {
  double worst = 0;
  for (auto [a, b] : pairs)
    for (int k : comps)
      worst =
          std::max(worst, std::abs((N.x[3 * a + k] - N.X[3 * a + k]) - (N.x[3 * b + k] - N.X[3 * b + k])));
  return worst;
}

// A twisted start: stretched 1 % along x, the rows given different transverse (z) and in-plane (x)
// velocities, no support: the strip flaps and vibrates freely.
void twist(Nodes& N) {
  for (int i = 0; i < N.count; ++i) {
    const double x = N.X[3 * i], row = N.X[3 * i + 1] > 0.01 ? 1.0 : -1.0;
    N.x[3 * i] = 1.01 * x;
    N.v[3 * i] = 0.05 * std::sin(3 * M_PI * x) * (1 + 0.5 * row);
    N.v[3 * i + 2] = 0.2 * std::sin(M_PI * x) + 0.3 * row * std::sin(2 * M_PI * x);
  }
}

std::array<double, 3> momentum(const Nodes& N) {
  std::array<double, 3> p{0, 0, 0};
  for (int i = 0; i < N.count; ++i)
    for (int k = 0; k < 3; ++k) p[k] += N.mass[i] * N.v[3 * i + k];
  return p;
}

}  // namespace

// With the tie, the rows' displacements across the extrusion (x, z) are the same at every step although the
// start moved the rows differently; the tie forces are internal, so the free strip's momentum stays that of
// the start (the tie averages the start's velocities by mass, keeping it); they do no work, so with no load
// and no support the work booked outside the elements is round-off, and the energy balance is exact.
TEST(ExtrudeTies, TwistedFreeStripMovesAsOneWithMomentumAndEnergyKept) {
  Scene s = loadSceneFromString(stripScene(kTie), "strip.yaml");
  Nodes& N = s.model->nodes;
  twist(N);
  const std::array<double, 3> p0 = momentum(N);  // of the twisted start, before the tie
  const auto pairs = rows(N);
  ASSERT_EQ(pairs.size(), 21u);
  ASSERT_GT(std::abs(N.v[3 * pairs[5].first + 2] - N.v[3 * pairs[5].second + 2]), 0.1);  // really twisted
  CentralDifference cd(*s.model, s.effectList(), s.constraints, CentralDifferenceSettings{});
  double pScale = 0;
  for (int i = 0; i < N.count; ++i)
    for (int k = 0; k < 3; ++k) pScale += N.mass[i] * std::abs(N.v[3 * i + k]);
  std::vector<double> vPrev = N.v;
  double worstRows = 0, worstMomentum = 0, worstBalance = 0, worstProduct = 0, worstExternal = 0;
  for (int n = 0; n < 4000; ++n) {
    ASSERT_TRUE(cd.step(1e9, true));
    worstRows = std::max(worstRows, rowDifference(N, pairs, {0, 2}));
    const auto p = momentum(N);
    for (int k = 0; k < 3; ++k) worstMomentum = std::max(worstMomentum, std::abs(p[k] - p0[k]) / pScale);
    const EnergyLedger& E = cd.energy();
    worstBalance = std::max(worstBalance, E.balanceError());
    if (n > 0) {
      // The ledger's product-form kinetic energy from the velocities the tie left, and no work outside the
      // elements: there is no load and no support, and the tie forces do none.
      double kx = 0;
      for (int d = 0; d < 3 * N.count; ++d) kx += 0.5 * N.mass[d / 3] * vPrev[d] * N.v[d];
      worstProduct = std::max(worstProduct, std::abs(E.kineticProduct - kx) / E.scale());
      worstExternal = std::max(worstExternal, std::abs(E.externalWork) / E.scale());
    }
    vPrev = N.v;
  }
  const double moved = rowDifference(N, {{pairs[0].first, pairs[10].first}}, {2});
  EXPECT_GT(moved, 1e-3);  // the strip did flap
  EXPECT_LE(worstRows, 1e-15 * moved) << "rows apart";
  EXPECT_LT(worstMomentum, 1e-13);
  EXPECT_LT(worstBalance, 1e-12);
  EXPECT_LT(worstProduct, 1e-13);
  EXPECT_LT(worstExternal, 1e-13);
}

// The same start without the tie: the rows move apart (what the tie prevents), so the check above is not
// void.
TEST(ExtrudeTies, TwistedFreeStripWithoutTheTieTwists) {
  Scene s = loadSceneFromString(stripScene("  []\n"), "strip.yaml");
  Nodes& N = s.model->nodes;
  twist(N);
  const auto pairs = rows(N);
  CentralDifference cd(*s.model, s.effectList(), s.constraints, CentralDifferenceSettings{});
  for (int n = 0; n < 4000; ++n) ASSERT_TRUE(cd.step(1e9, false));
  EXPECT_GT(rowDifference(N, pairs, {2}), 1e-3);
}
