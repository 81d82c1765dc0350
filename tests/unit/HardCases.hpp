#pragma once
// Shared by the hard-case suite (tests/unit/test_hard_*.cpp, ctest label `hard`): running a scene quietly and
// the checks that say what "stable" means there — a finite state, no inverted triangle, an energy bookkeeping
// that stayed bounded — plus the closed-form references several cases compare with.

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "TestScenes.hpp"
#include "structure/run/Simulation.hpp"
#include "structure/scene/Scene.hpp"

namespace fsi::test {

/// Runs a scene through the same loop as `fsi run` (instability checks included), output under the build
/// tree.
inline structure::RunResult runHard(structure::Scene& s, const std::string& name) {
  structure::RunOptions opt;
  opt.outDir = outDir("hard-" + name);
  opt.quiet = true;
  return structure::runSimulation(s, opt);
}

/// A number as text that reads back to the same double (for --set values).
inline std::string num(double v) {
  std::ostringstream o;
  o.precision(17);
  o << v;
  return o.str();
}

/// Every coordinate and velocity is finite.
inline bool finiteState(const structure::Model& m) {
  for (double v : m.nodes.x)
    if (!std::isfinite(v)) return false;
  for (double v : m.nodes.v)
    if (!std::isfinite(v)) return false;
  return true;
}

/// Triangles whose current normal points against their reference normal or whose area fell below
/// `areaFraction` of the reference area: elements turned inside out or collapsed. (A membrane may fold
/// during a run; at a pressurised static state none may be.)
inline int invertedTriangles(const structure::Model& m, double areaFraction = 1e-3) {
  const auto& c = m.membranes.conn;
  int bad = 0;
  for (int e = 0; e < m.membranes.count; ++e) {
    double n0[3], n[3];
    for (int which = 0; which < 2; ++which) {
      const std::vector<double>& p = which == 0 ? m.nodes.X : m.nodes.x;
      const double* a = &p[3 * c[3 * e]];
      const double* b = &p[3 * c[3 * e + 1]];
      const double* d = &p[3 * c[3 * e + 2]];
      const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
      const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
      double* out = which == 0 ? n0 : n;
      out[0] = u[1] * w[2] - u[2] * w[1];
      out[1] = u[2] * w[0] - u[0] * w[2];
      out[2] = u[0] * w[1] - u[1] * w[0];
    }
    const double a0 = std::sqrt(n0[0] * n0[0] + n0[1] * n0[1] + n0[2] * n0[2]);
    const double a1 = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double dot = n0[0] * n[0] + n0[1] * n[1] + n0[2] * n[2];
    if (!(dot > 0) || !(a1 > areaFraction * a0)) ++bad;
  }
  return bad;
}

/// Model node indices of a generator or Gmsh node group of mesh `mesh` (0: the first mesh).
inline std::vector<int> groupNodes(const structure::Model& m, const std::string& group, int mesh = 0) {
  std::vector<int> out;
  for (int i : m.meshes[std::size_t(mesh)].source.nodeGroups.at(group))
    out.push_back(m.meshes[std::size_t(mesh)].node[std::size_t(i)]);
  return out;
}

/// The run ended as `fsi run` exits 0 and its energy bookkeeping stayed bounded: the balance is round-off,
/// the elements created at most `created` of the energy supplied, the step-to-step velocity energy stayed
/// below its stable bound (4.3, docs/VALIDATION.md) and the state is finite.
inline void expectStableRun(const structure::RunResult& r, const structure::Scene& s, double created = 1e-3) {
  EXPECT_EQ(r.exitCode(), 0) << r.diagnosis;
  const auto& st = r.summary["stats"];
  EXPECT_LT(st["energy_balance_error"].get<double>(), 1e-9);
  EXPECT_LT(st["energy_created_max"].get<double>(), created);
  EXPECT_LT(st["energy_growth_max"].get<double>(), 4.3);
  EXPECT_TRUE(finiteState(*s.model));
}

/// Plane-strain bulge of a flat strip clamped along two parallel edges `span` apart under a follower pressure
/// p (Green-Lagrange strain, St Venant-Kirchhoff, c11t = E t/(1 − ν²)): the strip takes a circular arc of
/// half angle φ, stretch λ = φ/sin φ, whose tension t λ S = c11t λ(λ² − 1)/2 balances p R, R = span/(2 sin
/// φ). Returns the centre deflection R(1 − cos φ). Bisection on φ (the tension grows with φ, p R falls).
inline double arcDeflection(double span, double c11t, double p) {
  auto residual = [&](double phi) {
    const double lambda = phi / std::sin(phi);
    return c11t * lambda * (lambda * lambda - 1) / 2 - p * span / (2 * std::sin(phi));
  };
  double lo = 1e-6, hi = 1.5;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (residual(mid) < 0 ? lo : hi) = mid;
  }
  const double phi = 0.5 * (lo + hi);
  return span / (2 * std::sin(phi)) * (1 - std::cos(phi));
}

/// A flat, stress-free strip 0.2 m wide (x from 0 to 0.2), clamped along its long edges `clamped`, with
/// symmetry planes at its ends `ends` (y fixed there) so that it bulges in plane strain under 5 kPa applied
/// at once; E t = 1e5 N/m, ν = 0.3, damped to its static state. `generator` is the mesh.
inline std::string stripScene(const std::string& generator,
                              const std::string& clamped = "[strip/xmin, strip/xmax]",
                              const std::string& ends = "[strip/ymin, strip/ymax]") {
  return R"(materials:
  film: {type: membrane, young: 1.0e8, poisson: 0.3, thickness: 1.0e-3, density: 1000}
meshes:
  strip:
    generator: )" +
         generator + R"(
    material: film
constraints:
  - {nodes: )" +
         clamped +
         R"(, fix: all}
  - {nodes: )" +
         ends +
         R"(, fix: [y]}
effects:
  pressure: {triangles: strip, value: 5000}
  mass_damping: {alpha: 1500}
time:
  until_static: {tolerance: 1.0e-10, max_time: 1.0}
probes:
  deflection: {type: displacement, nodes: {nearest: [0.1, 0.01, 0]}, component: z}
)";
}
/// The strip's E t/(1 − ν²) [N/m] and its regular mesh: 20 × 2 squares of 1 cm, ruled.
constexpr double kStripC11t = 1.0e8 * 1.0e-3 / (1 - 0.3 * 0.3);
inline const std::string kRegularStrip =
    "{type: rectangle, size: [0.2, 0.02], center: [0.1, 0.01, 0], divisions: [20, 2]}";

}  // namespace fsi::test
