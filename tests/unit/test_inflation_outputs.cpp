// What an inflation run reports: summary.json's probe_extremes (each probe's largest and smallest value over
// the output rows and when) against a free fall's closed form, and the projected_diameter probe against a
// flat round canopy's constructed diameter.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "TestScenes.hpp"
#include "structure/roundcanopy/RoundCanopyGeometry.hpp"
#include "structure/run/Simulation.hpp"
#include "structure/scene/Scene.hpp"

using namespace fsi::structure;

namespace {

// A free 2 m chain falling from rest: every node at z0 − ½ g t² (central differences are exact for a constant
// acceleration), so the bottom node's height is largest at the first output row and smallest at the end.
const char* kFalling = R"(materials:
  line: {type: cable, young: 4.3e10, area: 3.0e-6, density: 906}
meshes:
  chain:
    generator: {type: cable_chain, points: [[0, 0, 0], [0, 0, -2]], divisions: [4]}
    cable_material: line
effects:
  gravity: {acceleration: [0, 0, -9.81]}
time: {end: 0.1}
output: {interval: 0.01, fields: displacement}
probes:
  bottom: {type: position, nodes: chain/end, component: z}
)";

TEST(InflationOutputs, ProbeExtremesAreTheLargestAndSmallestRowsAndTheirTimes) {
  Scene s = loadSceneFromString(kFalling, "fall.yaml");
  RunOptions opt;
  opt.outDir = fsi::test::outDir("probe-extremes");
  opt.quiet = true;
  const RunResult r = runSimulation(s, opt);
  ASSERT_EQ(r.exitCode(), 0) << r.diagnosis;
  const auto& e = r.summary.at("probe_extremes").at("bottom");
  EXPECT_NEAR(e.at("max").get<double>(), -2.0 - 0.5 * 9.81 * 0.01 * 0.01, 1e-9);
  EXPECT_NEAR(e.at("time_of_max").get<double>(), 0.01, 1e-12);
  EXPECT_NEAR(e.at("min").get<double>(), -2.0 - 0.5 * 9.81 * 0.1 * 0.1, 1e-9);
  EXPECT_NEAR(e.at("time_of_min").get<double>(), 0.1, 1e-12);
  EXPECT_NEAR(e.at("min").get<double>(), r.probes.at("bottom"), 1e-12) << "the end value is a row";
}

// A flat round canopy of 12 flat gores is the regular 12-gon: its projected diameter along the axis is the
// constructed diameter 2R (the radials' skirt ends are the farthest nodes), and seen edge-on (along y) its
// largest extent across, the same 2R.
TEST(InflationOutputs, ProjectedDiameterOfAFlatCanopyIsItsConstructedDiameter) {
  const std::string scene = R"(materials:
  cloth: {type: membrane, young: 5.0e8, poisson: 0.3, thickness: 1.0e-4, density: 400}
  cord: {type: cable, young: 2.0e9, area: 3.0e-6, density: 1140}
meshes:
  canopy:
    generator: {type: round_canopy, shape: flat, nominal_diameter: 2.0, gores: 12, vent_diameter: 0.2}
    material: cloth
    cable_material: cord
time: {end: 0.001}
probes:
  along_axis: {type: projected_diameter, triangles: canopy/canopy}
  edge_on: {type: projected_diameter, triangles: canopy/canopy, direction: [0, 2, 0]}
)";
  const Scene s = loadSceneFromString(scene, "flat.yaml");
  roundcanopy::RoundCanopyParams p;
  p.nominalDiameter = 2.0;
  p.gores = 12;
  p.ventDiameter = 0.2;
  const double dc = roundcanopy::designRoundCanopy(p).constructedDiameter;
  const auto v = evaluateProbes(s);
  EXPECT_NEAR(v.at("along_axis"), dc, 1e-12);
  EXPECT_NEAR(v.at("edge_on"), dc, 1e-12);
  EXPECT_NE(fsi::test::sceneError(fsi::test::replaced(scene, "[0, 2, 0]", "[0, 0, 0]"), "flat.yaml")
                .find("direction"),
            std::string::npos);
}

}  // namespace
