// The `extrude` constraint: a strip one element wide along an extrusion direction as a 2D model. The nodes
// at equal coordinates across the direction (the rows of the strip) form tie groups that move as one. Checked
// against references independent of the tie's code: rows identical at every step, momentum conservation of
// a free strip, the leapfrog's conserved energy of a linear-in-time system, the discrete string's closed-form
// deflection, and the located errors of bad input.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "TestScenes.hpp"
#include "structure/integrate/CentralDifference.hpp"
#include "structure/integrate/DynamicRelaxation.hpp"
#include "structure/run/Simulation.hpp"
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

// With mass damping (implicit in the update, so the group's update has the same factors): rows identical,
// balance exact, and the momentum decays by the damping's factor (1 − αΔ/2)/(1 + αΔ/2) per step, as every
// node's does without a tie.
TEST(ExtrudeTies, TwistedStripWithMassDampingKeepsTheBalance) {
  Scene s = loadSceneFromString(stripScene(kTie, "effects:\n  mass_damping: {alpha: 20}\ntime: {end: 1}\n"),
                                "strip.yaml");
  Nodes& N = s.model->nodes;
  twist(N);
  const auto pairs = rows(N);
  std::array<double, 3> p = momentum(N);
  CentralDifference cd(*s.model, s.effectList(), s.constraints, s.time.integrator);
  double worstRows = 0, worstBalance = 0, worstMomentum = 0, dtPrev = 0;
  for (int n = 0; n < 2000; ++n) {
    ASSERT_TRUE(cd.step(1e9, true));
    const double avg = 0.5 * (dtPrev + cd.lastDt()), a = 20;
    for (double& c : p) c *= (1 - 0.5 * a * avg) / (1 + 0.5 * a * avg);
    dtPrev = cd.lastDt();
    const auto now = momentum(N);
    for (int k = 0; k < 3; ++k) worstMomentum = std::max(worstMomentum, std::abs(now[k] - p[k]));
    worstRows = std::max(worstRows, rowDifference(N, pairs, {0, 2}));
    worstBalance = std::max(worstBalance, cd.energy().balanceError());
  }
  EXPECT_EQ(worstRows, 0.0);
  EXPECT_LT(worstBalance, 1e-12);
  EXPECT_LT(worstMomentum, 1e-15);
  EXPECT_GT(cd.energy().massDamping, 0.1 * cd.energy().initialKinetic);  // the damping did act
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

namespace {

struct StaticStrip {
  double maxDeflection = 0, parabolaError = 0, rowsApart = 0;
  std::map<std::string, double> probes;
  double rawRowReaction =
      0;  ///< Σ (f_int − f_ext)_z over the interior nodes of row y = 0, tie forces included
  long iterations = 0;
  StopReason reason = StopReason::NotConverged;
};

// The strip clamped at both ends after a 1 % stretch along x, under a pressure p = p0 + p1 X (+z, X the
// reference abscissa of each triangle's centroid), relaxed to its static state. Compares the deflection of
// every node with the discrete string's closed form.
// The free nodes of row y = 0 (the interior of the strip's edge), their reaction and load; the supports'
// reaction and the whole load.
const char* kProbes = R"(probes:
  row_reaction: {type: reaction, nodes: {box: {min: [0.01, -1, -1], max: [0.99, 0.01, 1]}}, component: z}
  row_load: {type: applied_load, nodes: {box: {min: [0.01, -1, -1], max: [0.99, 0.01, 1]}}, component: z}
  supports: {type: reaction, nodes: [strip/xmin, strip/xmax], component: z}
  load: {type: applied_load, nodes: strip, component: z}
  equilibrium: {type: equilibrium_error, supports: [strip/xmin, strip/xmax]}
)";

StaticStrip relaxStrip(const std::string& constraints, double p0, double p1) {
  const std::string yaml = stripScene(
      "  - {nodes: [strip/xmin, strip/xmax], fix: all}\n" + constraints,
      fmt::format(
          "effects:\n  chordwise_pressure: {{triangles: strip, dynamic_pressure: 1, chord: 1, cp: [[0, "
          "{}], [1, {}]]}}\nsolver: {{type: dynamic_relaxation, tolerance: 1.0e-11}}\n{}",
          -p0, -(p0 + p1), kProbes));  // suction (Cp < 0) pulls along the normal, +z
  Scene s = loadSceneFromString(yaml, "strip.yaml");
  Nodes& N = s.model->nodes;
  const double stretch = 1.01;
  for (int i = 0; i < N.count; ++i) N.x[3 * i] = stretch * N.X[3 * i];
  DynamicRelaxation dr(*s.model, s.effectList(), s.constraints, s.solver.relaxation);
  const RelaxationResult r = dr.run();
  StaticStrip out;
  out.reason = r.reason;
  out.iterations = r.iterations;
  // Tension per unit width of the stretched strip held across (plane strain, Saint Venant–Kirchhoff on the
  // Green–Lagrange strain): T = c11 t λ (λ² − 1) / 2, c11 = E / (1 − ν²). A taut string T w'' = −q(x) with
  // q linear in the current abscissa x = λX, q = p0 + p1 x/λ, clamped at x = 0 and L:
  //   w = p0 x (L − x) / (2T) + p1/λ · x (L² − x²) / (6T).
  // Its nodal values solve the discrete string exactly: the tied strip's lumped load at a node is q(x_i) h
  // (the four triangles' centroids sit symmetrically about it) and the three-point difference of a cubic is
  // exact. Small deflection (x, L current).
  const double c11 = 1.0e6 / (1 - 0.3 * 0.3), t = 1.0e-3, L = stretch * 1.0;
  const double T = c11 * t * stretch * (stretch * stretch - 1) / 2;
  for (int i = 0; i < N.count; ++i) {
    const double x = N.x[3 * i], w = N.x[3 * i + 2];
    const double exact = p0 * x * (L - x) / (2 * T) + p1 / stretch * x * (L * L - x * x) / (6 * T);
    out.maxDeflection = std::max(out.maxDeflection, w);
    out.parabolaError = std::max(out.parabolaError, std::abs(w - exact));
  }
  out.rowsApart = rowDifference(N, rows(N), {2});
  out.probes = evaluateProbes(s);
  for (int i = 0; i < N.count; ++i)
    if (N.X[3 * i + 1] < 0.01 && N.X[3 * i] > 0.01 && N.X[3 * i] < 0.99)
      out.rawRowReaction += N.fint[3 * i + 2] - N.fext[3 * i + 2];
  return out;
}

}  // namespace

// The tied strip is the 2D string: its static deflection is the discrete closed form to the small-deflection
// approximation (the deflection stretches the string by (8/3)(w/L)² ≈ 9e-7 on top of its 1 % strain, which
// raises the tension and lowers the deflection by about 9e-5 of itself), and its rows agree to round-off
// (accumulated over the relaxation's iterations). Without the tie (the same mesh, held across like the tied
// one) the rows of the ruled strip come apart: the pressure varies along x, and the two triangles of a
// square, whose centroids are at different x, load the rows differently — the defect the tie removes.
TEST(ExtrudeTies, TiedStripUnderPressureIsTheDiscreteString) {
  const double p0 = 0.025, p1 = 0.05;  // w_max ≈ 0.5 mm
  const StaticStrip tied = relaxStrip(kTieHold, p0, p1);
  ASSERT_EQ(tied.reason, StopReason::Static);
  std::printf("tied: w_max %.6g m, parabola error %.3g, rows %.3g, iterations %ld\n", tied.maxDeflection,
              tied.parabolaError, tied.rowsApart, tied.iterations);
  EXPECT_GT(tied.maxDeflection, 4e-4);
  EXPECT_LT(tied.parabolaError, 2e-4 * tied.maxDeflection);
  EXPECT_LE(tied.rowsApart, 1e-12 * tied.maxDeflection);
  const StaticStrip loose = relaxStrip("  - {nodes: strip, fix: y}\n", p0, p1);
  ASSERT_EQ(loose.reason, StopReason::Static);
  std::printf("untied: w_max %.6g m, parabola error %.3g, rows %.3g, iterations %ld\n", loose.maxDeflection,
              loose.parabolaError, loose.rowsApart, loose.iterations);
  EXPECT_GT(loose.rowsApart, 1e-4 * loose.maxDeflection);
  // Reactions: the tie forces between the rows are internal. On the free nodes of one row they are what
  // f_int − f_ext sums to (about 1 % of that row's load here: the rows are loaded differently), but a
  // `reaction` probe leaves them out — a free node has no support — and the supports balance the load.
  const auto& pr = tied.probes;
  EXPECT_GT(std::abs(tied.rawRowReaction), 1e-3 * pr.at("row_load"));
  EXPECT_LT(std::abs(pr.at("row_reaction")), 1e-6 * pr.at("row_load"));
  EXPECT_NEAR(pr.at("supports"), -pr.at("load"), 1e-6 * pr.at("load"));
  EXPECT_LT(pr.at("equilibrium"), 1e-6);
}

namespace {
bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}
const char* kEnds = "  - {nodes: [strip/xmin, strip/xmax], fix: all}\n";
}  // namespace

// Bad input: each error names the file, the entry's key path and what is wrong.
TEST(ExtrudeTies, BadInputIsALocatedError) {
  auto error = [](const std::string& constraints) {
    const std::string e = sceneError(stripScene(constraints), "strip.yaml");
    return e;
  };
  std::string e = error(std::string(kEnds) + "  - {nodes: strip, extrude: {direction: [0, 0, 0]}}\n");
  EXPECT_TRUE(has(e, "strip.yaml:")) << e;
  EXPECT_TRUE(has(e, "constraints[1].extrude.direction: must be a finite, non-zero vector")) << e;
  e = error("  - {nodes: strip, extrude: {direction: [.nan, 1, 0]}}\n");
  EXPECT_TRUE(has(e, "constraints[0].extrude.direction")) << e;
  e = error("  - {nodes: strip, extrude: {direction: [1.0e300, 1.0e300, 0]}}\n");
  EXPECT_TRUE(has(e, "constraints[0].extrude.direction: must be a finite, non-zero vector")) << e;
  e = error("  - {nodes: strip, extrude: {direction: [0, 1, 0], tolerance: -1}}\n");
  EXPECT_TRUE(has(e, "constraints[0].extrude.tolerance: must be >= 0")) << e;
  e = error("  - {nodes: strip, extrude: {direction: [0, 1, 0], hold_along: true}}\n");
  EXPECT_TRUE(has(e, "constraints[0].extrude")) << e;
  EXPECT_TRUE(has(e, "hold_along")) << e;
  e = error("  - {extrude: {direction: [0, 1, 0]}}\n");
  EXPECT_TRUE(has(e, "constraints[0]: missing required key 'nodes'")) << e;
  // One row only: no node has a partner along y.
  e = error("  - {nodes: strip/ymin, extrude: {direction: [0, 1, 0]}}\n");
  EXPECT_TRUE(has(e, "constraints[0].extrude: the 21 node(s) of this set form no tie group")) << e;
  // Along x, the rows' nodes do not line up with one another's either... but along y with a node of the
  // other row missing, that node is alone.
  e = error("  - {nodes: [strip/ymin, {nearest: [0.5, 0.05, 0]}], extrude: {direction: [0, 1, 0]}}\n");
  EXPECT_TRUE(has(e, "constraints[0].extrude: node")) << e;
  EXPECT_TRUE(has(e, "has no partner")) << e;
  // A tolerance wider than the node spacing joins neighbours in a chain whose ends are too far apart.
  e = error("  - {nodes: strip, extrude: {direction: [0, 1, 0], tolerance: 0.06}}\n");
  EXPECT_TRUE(has(e, "constraints[0].extrude:")) << e;
  EXPECT_TRUE(has(e, "beyond tolerance 0.06 m")) << e;
  // A node in two groups.
  e = error(
      "  - {nodes: strip, extrude: {direction: [0, 1, 0]}}\n"
      "  - {nodes: {box: {min: [0.4, -1, -1], max: [0.6, 1, 1]}}, extrude: {direction: [0, 1, 0]}}\n");
  EXPECT_TRUE(has(e, "constraints[1].extrude:")) << e;
  EXPECT_TRUE(has(e, "is already tied by constraints[0]")) << e;
  // Conflicts with other constraints, whatever their order in the list.
  e = error("  - {nodes: strip, extrude: {direction: [0, 1, 0]}}\n  - {nodes: strip/ymin, fix: z}\n");
  EXPECT_TRUE(has(e, "constraints[0].extrude:")) << e;
  EXPECT_TRUE(has(e, "is fixed in z (constraints[1]) but node")) << e;
  e = error(
      "  - {nodes: {nearest: [0.5, 0, 0]}, prescribe: {component: z, amplitude: 0.01}}\n"
      "  - {nodes: strip, extrude: {direction: [0, 1, 0]}}\n");
  EXPECT_TRUE(has(e, "constraints[1].extrude:")) << e;
  EXPECT_TRUE(has(e, "has a prescribed motion (constraints[0])")) << e;
  e = error(
      "  - {symmetry: {point: [0.5, 0, 0], normal: [1, 0, 1]}}\n"
      "  - {nodes: strip, extrude: {direction: [0, 1, 0]}}\n");
  EXPECT_TRUE(has(e, "constraints[1].extrude:")) << e;
  EXPECT_TRUE(has(e, "slides on the oblique symmetry plane of constraints[0]")) << e;
  // An oblique direction may not be combined with a component fixed on part of it.
  e = error("  - {nodes: strip, fix: x}\n  - {nodes: strip, extrude: {direction: [1, 1, 0]}}\n");
  EXPECT_TRUE(has(e, "constraints[1].extrude:")) << e;
  // The same constraints that are consistent load: a whole group fixed in z, clamped ends, holding along y.
  EXPECT_EQ(error(std::string(kEnds) + "  - {nodes: strip, extrude: {direction: [0, 1, 0], hold: true}}\n" +
                  "  - {nodes: [{nearest: [0.5, 0, 0]}, {nearest: [0.5, 0.05, 0]}], fix: z}\n"),
            "");
}

// An oblique extrusion: the strip lies in a plane tilted 30° about x, its width (the direction) along
// (0, cos 30°, sin 30°). The tie works on the components across the direction, not on dofs: the rows'
// displacements across it agree to round-off, the momentum of the free strip is kept and the balance exact.
TEST(ExtrudeTies, ObliqueDirectionTiesTheMotionAcrossIt) {
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6), w = 0.05;
  const std::string yaml = fmt::format(R"(materials:
  film: {{type: membrane, young: 1.0e6, poisson: 0.3, thickness: 1.0e-3, density: 1000}}
meshes:
  strip:
    generator: {{type: strip, path: [[0, 0, 0], [1, 0, 0]], divisions: [20], width: [0, {}, {}]}}
    material: film
constraints:
  - {{nodes: strip, extrude: {{direction: [0, {}, {}]}}}}
time: {{end: 1}}
)",
                                       w * c, w * s, c, s);
  Scene sc = loadSceneFromString(yaml, "oblique.yaml");
  Nodes& N = sc.model->nodes;
  const double normal[3] = {0, -s, c};
  for (int i = 0; i < N.count; ++i) {
    const double x = N.X[3 * i], row = N.X[3 * i + 1] > 0.01 ? 1.0 : -1.0;
    N.x[3 * i] = 1.01 * x;
    N.v[3 * i] = 0.05 * std::sin(3 * M_PI * x) * (1 + 0.5 * row);
    const double vn = 0.2 * std::sin(M_PI * x) + 0.3 * row * std::sin(2 * M_PI * x);
    for (int k = 1; k < 3; ++k) N.v[3 * i + k] = vn * normal[k];
  }
  const std::array<double, 3> p0 = momentum(N);
  double pScale = 0;
  for (int i = 0; i < N.count; ++i)
    for (int k = 0; k < 3; ++k) pScale += N.mass[i] * std::abs(N.v[3 * i + k]);
  std::map<double, std::vector<int>> byX;
  for (int i = 0; i < N.count; ++i) byX[N.X[3 * i]].push_back(i);
  ASSERT_EQ(byX.size(), 21u);
  CentralDifference cd(*sc.model, sc.effectList(), sc.constraints, CentralDifferenceSettings{});
  double worstRows = 0, worstMomentum = 0, worstBalance = 0, moved = 0;
  for (int n = 0; n < 4000; ++n) {
    ASSERT_TRUE(cd.step(1e9, true));
    for (const auto& [x, g] : byX) {
      ASSERT_EQ(g.size(), 2u);
      double u[2][2];  // x and normal displacement of each row
      for (int r = 0; r < 2; ++r) {
        const int i = g[std::size_t(r)];
        u[r][0] = N.x[3 * i] - N.X[3 * i];
        u[r][1] = 0;
        for (int k = 1; k < 3; ++k) u[r][1] += (N.x[3 * i + k] - N.X[3 * i + k]) * normal[k];
      }
      worstRows = std::max({worstRows, std::abs(u[0][0] - u[1][0]), std::abs(u[0][1] - u[1][1])});
      moved = std::max(moved, std::abs(u[0][1]));
    }
    const auto p = momentum(N);
    for (int k = 0; k < 3; ++k) worstMomentum = std::max(worstMomentum, std::abs(p[k] - p0[k]) / pScale);
    worstBalance = std::max(worstBalance, cd.energy().balanceError());
  }
  EXPECT_GT(moved, 1e-3);
  EXPECT_LT(worstRows, 1e-12 * moved);
  EXPECT_LT(worstMomentum, 1e-13);
  EXPECT_LT(worstBalance, 1e-12);
}
