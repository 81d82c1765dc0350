// The probes the parafoil cases report: line tension against EA·ε, the reaction moment against r × F, the
// pitch angle of a chord turned by a known angle.
#include <gtest/gtest.h>

#include <cmath>

#include "TestScenes.hpp"
#include "structure/run/Simulation.hpp"
#include "structure/scene/Scene.hpp"

using namespace fsi::structure;

namespace {

const char* kChain = R"(materials:
  line: {type: cable, young: 4.0e10, area: 2.5e-6, density: 900}
meshes:
  l:
    generator: {type: cable_chain, points: [[0, 0, 0], [1, 0, 0]], divisions: [4]}
    cable_material: line
constraints:
  - {nodes: l/end, fix: all}
effects:
  nodal_forces: {nodes: l/end, force: [0, 0, 10]}
probes:
  t_max: {type: line_tension, lines: l}
  t_sum: {type: line_tension, lines: l/all, reduce: sum}
  m_y: {type: reaction_moment, nodes: l/end, about: [0, 0, 0], component: y}
  m_y_shifted: {type: reaction_moment, nodes: l/end, about: [1, 0, 0], component: y}
  m_y_about_start: {type: reaction_moment, nodes: l/end, about: l/start, component: y}
  m_y_about_end: {type: reaction_moment, nodes: l/end, about: l/end, component: y}
  load_z: {type: applied_load, nodes: l, component: z}
  reaction_z: {type: reaction, nodes: l, component: z}
  balance: {type: equilibrium_error, supports: l/end}
  unbalanced: {type: equilibrium_error, supports: l/start}
time: {end: 1.0e-3}
)";

}  // namespace

TEST(ParafoilProbes, LineTensionIsEATimesStrain) {
  Scene scene = loadSceneFromString(kChain, "chain.yaml");
  Nodes& N = scene.model->nodes;
  for (int i = 0; i < N.count; ++i) N.x[3 * i] = 1.01 * N.X[3 * i];  // 1 % stretch of every cable
  const auto p = evaluateProbes(scene);
  const double T = 4.0e10 * 2.5e-6 * 0.01;
  EXPECT_NEAR(p.at("t_max"), T, T * 1e-10);
  EXPECT_NEAR(p.at("t_sum"), 4 * T, 4 * T * 1e-10);
}

TEST(ParafoilProbes, ReactionMomentIsRCrossTheReaction) {
  // The fixed end (1, 0, 0) carries F = (0, 0, 10): its reaction is −F, the moment about the origin
  // (1, 0, 0) × (0, 0, −10) = (0, 10, 0), about the end itself zero.
  Scene scene = loadSceneFromString(kChain, "chain.yaml");
  evaluateEffects(scene.model->nodes, scene.effectList(), 0.0, 1.0, false);
  const auto p = evaluateProbes(scene);
  EXPECT_NEAR(p.at("m_y"), 10.0, 1e-12);
  EXPECT_NEAR(p.at("m_y_shifted"), 0.0, 1e-12);
  // About a one-node set: its reference position (the start sits at the origin, the end at (1, 0, 0)).
  EXPECT_NEAR(p.at("m_y_about_start"), 10.0, 1e-12);
  EXPECT_NEAR(p.at("m_y_about_end"), 0.0, 1e-12);
  // Global equilibrium at rest: the reactions and the applied load cancel.
  EXPECT_NEAR(p.at("load_z"), 10.0, 1e-12);
  EXPECT_NEAR(p.at("reaction_z") + p.at("load_z"), 0.0, 1e-12);
  EXPECT_NEAR(p.at("balance"), 0.0, 1e-14);
  // The free end carries no reaction: the whole load is out of balance.
  EXPECT_NEAR(p.at("unbalanced"), 1.0, 1e-14);
}

TEST(ParafoilProbes, MomentAboutASetOfMoreThanOneNodeIsALocatedError) {
  const std::string e = fsi::test::sceneError(
      fsi::test::replaced(kChain, "about: [0, 0, 0], component: y}", "about: l/all, component: y}"),
      "chain.yaml");
  EXPECT_NE(e.find("chain.yaml"), std::string::npos) << e;
  EXPECT_NE(e.find("probes.m_y.about"), std::string::npos) << e;
  EXPECT_NE(e.find("5 nodes"), std::string::npos) << e;
}

TEST(ParafoilProbes, PitchAngleOfATurnedChord) {
  const std::string yaml = R"(materials:
  film: {type: membrane, young: 1.0e8, poisson: 0.3, thickness: 1.0e-3, density: 1000}
meshes:
  plate:
    generator: {type: rectangle, size: [1, 2], divisions: [4, 4], center: [0.5, 0, 0]}
    material: film
constraints:
  - {nodes: plate/boundary, fix: all}
probes:
  pitch: {type: pitch_angle, from: plate/xmin, to: plate/xmax}
time: {end: 1.0e-3}
)";
  Scene scene = loadSceneFromString(yaml, "plate.yaml");
  EXPECT_NEAR(evaluateProbes(scene).at("pitch"), 0.0, 1e-12);
  // Nose up by 7°: the trailing edge (x = 1) goes down.
  const double th = 7.0 * std::acos(-1.0) / 180.0;
  Nodes& N = scene.model->nodes;
  for (int i = 0; i < N.count; ++i) {
    const double x = N.X[3 * i], z = N.X[3 * i + 2];
    N.x[3 * i] = x * std::cos(th) + z * std::sin(th);
    N.x[3 * i + 2] = -x * std::sin(th) + z * std::cos(th);
  }
  EXPECT_NEAR(evaluateProbes(scene).at("pitch"), 7.0, 1e-12);
}
