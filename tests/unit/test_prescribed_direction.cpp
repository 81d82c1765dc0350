// `prescribe: {direction: [dx, dy, dz], ...}`: a node (a brake toggle) pulled along a line. The whole
// displacement is prescribed, a·f(t)·d/|d|, so the node stays on the line even under a load across it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "TestScenes.hpp"
#include "structure/integrate/CentralDifference.hpp"
#include "structure/model/Error.hpp"
#include "structure/scene/Scene.hpp"

using namespace fsi::structure;

namespace {

// A horizontal line fixed at its start; its end pulled 5 cm along [1, 1, 0] (ramped over 10 ms) while a
// 100 N load pushes it down, across the line of pull.
const char* kToggle = R"(materials:
  line: {type: cable, young: 4.3e10, area: 3.0e-6, density: 906}
meshes:
  brake:
    generator: {type: cable_chain, points: [[0, 0, 0], [1, 0, 0]], divisions: [4]}
    cable_material: line
constraints:
  - {nodes: brake/start, fix: all}
  - {nodes: brake/end, prescribe: {direction: [1, 1, 0], amplitude: 0.05, function: {type: ramp, duration: 0.01}}}
effects:
  nodal_forces: {nodes: brake/end, force: [0, 0, -100]}
time: {end: 0.02}
)";

std::string errorOf(const std::string& yaml) {
  return fsi::test::sceneError(yaml, "toggle.yaml");
}

using fsi::test::replaced;

}  // namespace

TEST(PrescribedDirection, NodeFollowsTheLineExactlyUnderALoadAcrossIt) {
  Scene s = loadSceneFromString(kToggle, "toggle.yaml");
  Model& m = *s.model;
  int end = -1;
  for (int i = 0; i < m.nodes.count; ++i)
    if (m.nodes.X[3 * i] == 1.0) end = i;
  ASSERT_GE(end, 0);
  const double h = 1.0 / std::sqrt(2.0);
  const double dir[3] = {h, h, 0};
  CentralDifference cd(m, s.effectList(), s.constraints, CentralDifferenceSettings{});
  int steps = 0;
  double maxDev = 0;
  while (cd.time() < 0.02) {
    ASSERT_TRUE(cd.step(0.02, false));
    ++steps;
    const double t = cd.time();
    const double u = 0.05 * std::min(t / 0.01, 1.0);  // a·f(t), f the ramp
    for (int k = 0; k < 3; ++k) {
      const double dev = std::abs(m.nodes.x[3 * end + k] - (m.nodes.X[3 * end + k] + u * dir[k]));
      maxDev = std::max(maxDev, dev);
    }
  }
  EXPECT_GT(steps, 10);
  EXPECT_LE(maxDev, 1e-15) << "largest deviation from X + a·f(t)·d̂";
  // The load across the line did work on nothing: the node has no velocity component along z.
  EXPECT_EQ(m.nodes.v[3 * end + 2], 0.0);
  // Meanwhile the free nodes did move under the line's pull (the constraint is not a fix of the line).
  double moved = 0;
  for (int i = 0; i < m.nodes.count; ++i)
    if (i != end && m.nodes.X[3 * i] > 0) moved = std::max(moved, std::abs(m.nodes.x[3 * i + 1]));
  EXPECT_GT(moved, 1e-4);
}

TEST(PrescribedDirection, ComponentStillPrescribesOnlyItsComponent) {
  Scene s = loadSceneFromString(replaced(kToggle, "direction: [1, 1, 0]", "component: y"), "toggle.yaml");
  ASSERT_EQ(s.constraints.prescribed.size(), 1u);
  EXPECT_EQ(s.constraints.prescribed[0].component, 1);
  EXPECT_EQ(s.constraints.prescribed[0].amplitude, 0.05);
}

TEST(PrescribedDirection, BadDirectionsAreLocated) {
  const std::string zero = errorOf(replaced(kToggle, "[1, 1, 0]", "[0, 0, 0]"));
  EXPECT_NE(zero.find("toggle.yaml:9"), std::string::npos) << zero;
  EXPECT_NE(zero.find("direction"), std::string::npos) << zero;
  EXPECT_NE(zero.find("non-zero"), std::string::npos) << zero;
  const std::string nan = errorOf(replaced(kToggle, "[1, 1, 0]", "[.nan, 1, 0]"));
  EXPECT_NE(nan.find("toggle.yaml:9"), std::string::npos) << nan;
  const std::string both =
      errorOf(replaced(kToggle, "direction: [1, 1, 0]", "direction: [1, 1, 0], component: x"));
  EXPECT_NE(both.find("toggle.yaml:9"), std::string::npos) << both;
  EXPECT_NE(both.find("either"), std::string::npos) << both;
  const std::string neither = errorOf(replaced(kToggle, "direction: [1, 1, 0], ", ""));
  EXPECT_NE(neither.find("either"), std::string::npos) << neither;
  const std::string typo = errorOf(replaced(kToggle, "direction:", "directoin:"));
  EXPECT_NE(typo.find("toggle.yaml:9"), std::string::npos) << typo;
}
