// The laplace probe against closed forms: a flat film stretched and rolled onto a cylinder of radius R has a
// uniform St Venant–Kirchhoff stress (Green strains of the two stretches), so its hoop resultant N_θ, its
// curvature 1/R and the follower pressure on it are known: the probe must return them, and (N:b)/p = N_θ/(R
// p). The area-weighted stress mean against a hand sum on a graded mesh.
#include <gtest/gtest.h>

#include <cmath>

#include "structure/elements/MembraneForces.hpp"
#include "structure/model/Error.hpp"
#include "structure/run/Simulation.hpp"
#include "structure/scene/Scene.hpp"

using namespace fsi::structure;

namespace {

const char* kFilm = R"(materials:
  film: {type: membrane, young: 2.0e8, poisson: 0.3, thickness: 1.0e-3, density: 1000}
meshes:
  plate:
    generator: {type: rectangle, size: [0.4, 0.4], divisions: [40, 40]}
    material: film
effects:
  pressure: {triangles: plate, value: 500.0}
probes:
  ratio: {type: laplace, nodes: {nearest: [0.01, 0.01, 0]}, triangles: plate, quantity: ratio}
  hoop_radius: {type: laplace, nodes: {nearest: [0.01, 0.01, 0]}, triangles: plate, quantity: radius,
                direction: [0, 1, 0]}
  hoop_tension: {type: laplace, nodes: {nearest: [0.01, 0.01, 0]}, triangles: plate, quantity: tension,
                 direction: [0, 1, 0]}
  axial_tension: {type: laplace, nodes: {nearest: [0.01, 0.01, 0]}, triangles: plate, quantity: tension,
                  direction: [1, 0, 0], rings: 3}
  pressure: {type: laplace, nodes: {nearest: [0.01, 0.01, 0]}, triangles: plate, quantity: pressure}
  simple: {type: laplace, nodes: {nearest: [0.01, 0.01, 0]}, triangles: plate, quantity: simple_ratio,
           direction: [0, 1, 0]}
time: {end: 1.0e-3}
)";

}  // namespace

TEST(LaplaceProbe, StretchedCylinderGivesItsHoopTensionCurvatureAndPressure) {
  Scene scene = loadSceneFromString(kFilm, "film.yaml");
  Nodes& N = scene.model->nodes;
  const double R = 0.5, l1 = 1.01, l2 = 1.02;  // radius; axial and hoop stretch
  // X = (u, v, 0) -> x = (l1 u, R sin(l2 v / R), R cos(l2 v / R) − R): a cylinder about the axis (·, 0, −R),
  // its normal (the rectangle's +z) pointing away from the axis: a bulge seen from outside.
  for (int i = 0; i < N.count; ++i) {
    const double u = N.X[3 * i], v = N.X[3 * i + 1];
    N.x[3 * i] = l1 * u;
    N.x[3 * i + 1] = R * std::sin(l2 * v / R);
    N.x[3 * i + 2] = R * std::cos(l2 * v / R) - R;
  }
  evaluateEffects(N, scene.effectList(), 0.0, 1.0, false);
  const auto p = evaluateProbes(scene);
  // Plane-stress SVK: S = E/(1−ν²) [E11 + ν E22, E22 + ν E11]; Cauchy σ = F S Fᵀ / J with J = l1 l2 (the
  // thickness is not updated), resultant N = σ t: N_θ = l2² S22 t / (l1 l2).
  const double E = 2.0e8, nu = 0.3, t = 1.0e-3, c = E / (1 - nu * nu);
  const double E11 = 0.5 * (l1 * l1 - 1), E22 = 0.5 * (l2 * l2 - 1);
  const double S11 = c * (E11 + nu * E22), S22 = c * (E22 + nu * E11);
  const double Nhoop = l2 * S22 * t / l1, Naxial = l1 * S11 * t / l2;
  // Flat triangles span chords, not arcs: the hoop stretch of the mesh is l2·(1 − θ²/24) (θ = h/R = 0.02), a
  // relative change of the hoop Green strain of about 1.7e-3 — the bound of the stress error.
  EXPECT_NEAR(p.at("hoop_tension"), Nhoop, 2e-3 * Nhoop);
  EXPECT_NEAR(p.at("axial_tension"), Naxial, 2e-3 * Naxial);
  // The curvature and the nodal pressure carry the discretisation error of a 10 mm mesh on R = 0.5 m.
  EXPECT_NEAR(p.at("hoop_radius"), R, 1e-3 * R);
  EXPECT_NEAR(p.at("pressure"), 500.0, 500.0 * 2e-3);
  EXPECT_NEAR(p.at("ratio"), Nhoop / (R * 500.0), 3e-3 * Nhoop / (R * 500.0));
  // Along the hoop the one-direction relation is the whole story on a cylinder (no axial curvature).
  EXPECT_NEAR(p.at("simple"), p.at("ratio"), 1e-3 * p.at("ratio"));
}

TEST(LaplaceProbe, ANodeOnTheEdgeOfTheSurfaceIsRefusedAtLoad) {
  std::string yaml = kFilm;
  const std::string from = "ratio: {type: laplace, nodes: {nearest: [0.01, 0.01, 0]}";
  yaml.replace(yaml.find(from), from.size(), "ratio: {type: laplace, nodes: {nearest: [0.2, 0.2, 0]}");
  try {
    loadSceneFromString(yaml, "film.yaml");
    FAIL() << "a corner node was accepted";
  } catch (const fsi::InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("film.yaml:"), std::string::npos) << m;
    EXPECT_NE(m.find("probes.ratio.nodes"), std::string::npos) << m;
    EXPECT_NE(m.find("on the edge"), std::string::npos) << m;
  }
}

TEST(StressProbe, TheMeanIsWeightedByArea) {
  // Two triangles of a strip, one stretched, one not: the mean is the area-weighted one.
  const std::string yaml = R"(materials:
  film: {type: membrane, young: 1.0e8, poisson: 0.0, thickness: 1.0e-3, density: 1000}
meshes:
  plate:
    generator: {type: rectangle, size: [1, 1], divisions: [2, 1]}
    material: film
probes:
  mean: {type: stress, triangles: plate, reduce: mean}
  max: {type: stress, triangles: plate}
time: {end: 1.0e-3}
)";
  Scene scene = loadSceneFromString(yaml, "plate.yaml");
  Nodes& N = scene.model->nodes;
  // Stretch by 1 % in x everywhere: the same stress in every triangle, so any weighting gives it...
  for (int i = 0; i < N.count; ++i) N.x[3 * i] = 1.01 * N.X[3 * i];
  const auto uniform = evaluateProbes(scene);
  EXPECT_NEAR(uniform.at("mean"), uniform.at("max"), 1e-9 * uniform.at("max"));
  // ... then pull one node far out: the triangles change area and stress unequally; compare with the sum.
  N.x[3 * (N.count - 1) + 2] += 0.3;
  const auto p = evaluateProbes(scene);
  MembraneStressField s;
  membraneStresses(scene.model->membranes, N.x.data(), s);
  double num = 0, den = 0;
  const auto& T = scene.model->membranes;
  for (int e = 0; e < T.count; ++e) {
    const int* c = &T.conn[3 * e];
    double a[3], b[3];
    for (int k = 0; k < 3; ++k) {
      a[k] = N.x[3 * c[1] + k] - N.x[3 * c[0] + k];
      b[k] = N.x[3 * c[2] + k] - N.x[3 * c[0] + k];
    }
    const double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2],
                 cz = a[0] * b[1] - a[1] * b[0];
    const double area = 0.5 * std::sqrt(cx * cx + cy * cy + cz * cz);
    num += area * s.principal[2 * e];
    den += area;
  }
  EXPECT_NEAR(p.at("mean"), num / den, 1e-12 * std::abs(num / den));
}
