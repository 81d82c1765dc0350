// The scene schema comes from the registries (effects, probes, generators): their names and keys are the
// valid choices of the scene file, with "did you mean". The top-level key list includes `coupling`, and a
// misspelt section is reported as such before anything else is read. Probe components are named.
#include <gtest/gtest.h>

#include <cmath>

#include "TestScenes.hpp"
#include "structure/model/Error.hpp"
#include "structure/probes/ProbeKinds.hpp"
#include "structure/run/Simulation.hpp"
#include "structure/scene/GeneratorKinds.hpp"
#include "structure/scene/Scene.hpp"
#include "structure/scene/effects/EffectKinds.hpp"

using namespace fsi::structure;
using fsi::test::drumScene;

namespace {

const std::string kTime = "time: {end: 0.01}\n";  // line 9 after the 8 lines of drumScene

std::string errorOf(const std::string& yaml) {
  return fsi::test::sceneError(yaml, "case.yaml");
}

bool has(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

}  // namespace

TEST(SceneSchema, MisspeltCouplingSectionSuggestsCoupling) {
  // The top-level key list used to leave out `coupling`: no suggestion, and not listed as valid.
  const std::string e = errorOf(drumScene(kTime + "couplng: {interface: sheet}\n"));
  EXPECT_TRUE(has(e, "case.yaml:10:1: couplng: unknown key 'couplng' (did you mean 'coupling'?)")) << e;
  EXPECT_TRUE(has(e, "valid keys here: title, materials, meshes, sets, constraints, effects, coupling,"))
      << e;
}

TEST(SceneSchema, MisspeltSectionIsReportedBeforeTheSectionItHides) {
  // `tme:` used to be reported as a missing `time:` section, without a word about the typo.
  const std::string e = errorOf(drumScene("tme: {end: 0.01}\n"));
  EXPECT_TRUE(has(e, "case.yaml:9:1: tme: unknown key 'tme' (did you mean 'time'?)")) << e;
}

TEST(SceneSchema, EffectNamesAndKeysComeFromTheRegistry) {
  std::string e = errorOf(drumScene(kTime + "effects: {gravty: {acceleration: [0, 0, -9.81]}}\n"));
  EXPECT_TRUE(has(e, "case.yaml:10:") && has(e, "unknown key 'gravty' (did you mean 'gravity'?)")) << e;
  for (const EffectKind& k : effectKinds()) EXPECT_TRUE(has(e, k.name)) << k.name << ": " << e;

  e = errorOf(drumScene(kTime + "effects: {pressure: {triangles: sheet, value: 1, fuction: 2}}\n"));
  EXPECT_TRUE(has(e, "effects.pressure.fuction: unknown key 'fuction' (did you mean 'function'?)")) << e;
  for (const EffectKind& k : effectKinds()) {
    if (k.name != "pressure") continue;
    for (const auto& key : k.keys) EXPECT_TRUE(has(e, key)) << key << ": " << e;
  }
}

TEST(SceneSchema, ProbeTypesAndKeysComeFromTheRegistry) {
  std::string e = errorOf(drumScene(kTime + "probes: {p: {type: displacment, nodes: sheet}}\n"));
  EXPECT_TRUE(has(e, "probes.p.type") && has(e, "did you mean 'displacement'")) << e;
  for (const ProbeKind& k : probeKinds()) EXPECT_TRUE(has(e, k.name)) << k.name << ": " << e;

  e = errorOf(drumScene(kTime + "probes: {p: {type: volume, triangles: sheet, centre: [0, 0, 0]}}\n"));
  EXPECT_TRUE(has(e, "probes.p.centre: unknown key 'centre' (did you mean 'center'?)")) << e;
}

TEST(SceneSchema, GeneratorTypesAndKeysComeFromTheRegistry) {
  std::string e = errorOf(fsi::test::replaced(drumScene(kTime), "type: rectangle", "type: rectangel"));
  EXPECT_TRUE(has(e, "meshes.sheet.generator.type") && has(e, "did you mean 'rectangle'")) << e;
  for (const GeneratorKind& k : generatorKinds()) EXPECT_TRUE(has(e, k.name)) << k.name << ": " << e;

  e = errorOf(fsi::test::replaced(drumScene(kTime), "pattern: cross", "pattern: cross, centre: [0, 0, 0]"));
  EXPECT_TRUE(has(e, "meshes.sheet.generator.centre: unknown key 'centre' (did you mean 'center'?)")) << e;
}

TEST(SceneSchema, ProbeComponentsReportTheNamedComponent) {
  // The corner (0.5, 0.5, 0) of the 1 m square moved by (0.3, 0, 0.4), with a reaction (3, 0, 4) on it.
  const std::string corner = "{nearest: [0.5, 0.5, 0]}";
  std::string probes = "probes:\n";
  for (const std::string c : {"x", "y", "z", "magnitude"}) {
    probes += "  u_" + c + ": {type: displacement, nodes: " + corner + ", component: " + c + "}\n";
    probes += "  x_" + c + ": {type: position, nodes: " + corner + ", component: " + c + "}\n";
    probes += "  r_" + c + ": {type: reaction, nodes: " + corner + ", component: " + c + "}\n";
  }
  probes +=
      "  u_radial: {type: displacement, nodes: " + corner + ", component: radial, center: [0.5, 0, 0]}\n";
  probes += "  x_radial: {type: position, nodes: " + corner + ", component: radial, center: [0.5, 0, 0]}\n";
  Scene s = loadSceneFromString(drumScene(kTime + probes), "case.yaml");
  Nodes& N = s.model->nodes;
  int n = -1;
  for (int i = 0; i < N.count; ++i)
    if (std::abs(N.X[3 * i] - 0.5) < 1e-12 && std::abs(N.X[3 * i + 1] - 0.5) < 1e-12) n = i;
  ASSERT_GE(n, 0);
  ASSERT_EQ(N.X[3 * n + 2], 0.0);
  const double u[3] = {0.3, 0.0, 0.4}, r[3] = {3.0, 0.0, 4.0};
  for (int k = 0; k < 3; ++k) {
    N.x[3 * n + k] = N.X[3 * n + k] + u[k];
    N.fint[3 * n + k] = r[k];
    N.fext[3 * n + k] = 0.0;
  }
  const auto v = evaluateProbes(s);
  EXPECT_NEAR(v.at("u_x"), 0.3, 1e-15);
  EXPECT_NEAR(v.at("u_y"), 0.0, 1e-15);
  EXPECT_NEAR(v.at("u_z"), 0.4, 1e-15);
  EXPECT_NEAR(v.at("u_magnitude"), 0.5, 1e-15);
  EXPECT_NEAR(v.at("x_x"), 0.8, 1e-15);
  EXPECT_NEAR(v.at("x_y"), 0.5, 1e-15);
  EXPECT_NEAR(v.at("x_z"), 0.4, 1e-15);
  EXPECT_NEAR(v.at("x_magnitude"), std::sqrt(0.64 + 0.25 + 0.16), 1e-15);
  EXPECT_NEAR(v.at("r_x"), 3.0, 1e-15);
  EXPECT_NEAR(v.at("r_y"), 0.0, 1e-15);
  EXPECT_NEAR(v.at("r_z"), 4.0, 1e-15);
  EXPECT_NEAR(v.at("r_magnitude"), 5.0, 1e-14);
  // From (0.5, 0, 0): the node was 0.5 away and is now |(0.3, 0.5, 0.4)| away.
  EXPECT_NEAR(v.at("x_radial"), std::sqrt(0.09 + 0.25 + 0.16), 1e-15);
  EXPECT_NEAR(v.at("u_radial"), std::sqrt(0.09 + 0.25 + 0.16) - 0.5, 1e-15);
}
