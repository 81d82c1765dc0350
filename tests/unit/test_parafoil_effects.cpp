// The parafoil's load effects through a scene: line drag on a line across the wind, body drag on a payload
// node, an outer-flow Cp table on a plate — each total against its closed form — and located errors for the
// line selector and the effect keys.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "structure/model/Error.hpp"
#include "structure/scene/Scene.hpp"

using namespace fsi::structure;

namespace {

// Total external force of the scene's effects at the reference state, at rest.
std::array<double, 3> totalLoad(Scene& scene) {
  Nodes& N = scene.model->nodes;
  evaluateEffects(N, scene.effectList(), 0.0, 1.0, false);
  std::array<double, 3> t{0, 0, 0};
  for (int i = 0; i < N.count; ++i)
    for (int k = 0; k < 3; ++k) t[k] += N.fext[3 * i + k];
  return t;
}

const char* kLine = R"(materials:
  line: {type: cable, young: 4.3e10, area: 3.0e-6, density: 906}
meshes:
  riser:
    generator: {type: cable_chain, points: [[0, 0, 0], [0, 0, -3]], divisions: [6]}
    cable_material: line
constraints:
  - {nodes: riser/start, fix: all}
effects:
  line_drag: {lines: riser, diameter: 2.0e-3, cd: 1.1, wind: [12, 0, 0], density: 1.2}
  body_drag: {nodes: riser/end, drag_area: 0.4, wind: [12, 0, 0], density: 1.2}
time: {end: 1.0e-3}
)";

}  // namespace

TEST(ParafoilEffects, LineAndBodyDragTotals) {
  Scene scene = loadSceneFromString(kLine, "drag.yaml");
  const auto t = totalLoad(scene);
  const double line = 0.5 * 1.2 * 1.1 * 2.0e-3 * 144.0 * 3.0, body = 0.5 * 1.2 * 0.4 * 144.0;
  EXPECT_NEAR(t[0], line + body, (line + body) * 1e-13);
  EXPECT_NEAR(t[1], 0.0, 1e-14);
  EXPECT_NEAR(t[2], 0.0, 1e-14);
}

TEST(ParafoilEffects, ChordwiseCpTablePushesAgainstTheNormal) {
  // A 1 m × 2 m plate, normal +z (the flow above it), Cp = −1 (suction) at the leading edge falling linearly
  // to 0 at the trailing edge: the flow pulls the plate up with q·∫|Cp| dx·b = q·0.5·2.
  const std::string yaml = R"(materials:
  film: {type: membrane, young: 1.0e8, poisson: 0.3, thickness: 1.0e-3, density: 1000}
meshes:
  plate:
    generator: {type: rectangle, size: [1, 2], divisions: [8, 16], center: [0.5, 0, 0], pattern: alternating}
    material: film
constraints:
  - {nodes: plate/boundary, fix: all}
effects:
  chordwise_pressure: {triangles: plate, dynamic_pressure: 80, cp: [[0, -1], [1, 0]], chord: 1.0}
time: {end: 1.0e-3}
)";
  Scene scene = loadSceneFromString(yaml, "cp.yaml");
  const auto t = totalLoad(scene);
  EXPECT_NEAR(t[2], 80.0 * 0.5 * 2.0, 1e-10);
  EXPECT_NEAR(t[0], 0.0, 1e-12);
}

TEST(ParafoilEffects, LineSelectorAndKeysAreLocated) {
  auto error = [](std::string text, const std::string& from, const std::string& to) {
    text.replace(text.find(from), from.size(), to);
    try {
      loadSceneFromString(text, "drag.yaml");
    } catch (const fsi::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string group = error(kLine, "lines: riser,", "lines: riser/al,");
  EXPECT_NE(group.find("drag.yaml:10"), std::string::npos) << group;
  EXPECT_NE(group.find("did you mean 'all'"), std::string::npos) << group;
  const std::string key = error(kLine, "diameter: 2.0e-3", "diametre: 2.0e-3");
  EXPECT_NE(key.find("did you mean 'diameter'"), std::string::npos) << key;
  const std::string value = error(kLine, "drag_area: 0.4", "drag_area: -1");
  EXPECT_NE(value.find("drag.yaml:11"), std::string::npos) << value;
  const std::string kind = error(kLine, "line_drag:", "line_dragg:");
  EXPECT_NE(kind.find("did you mean 'line_drag'"), std::string::npos) << kind;
}
