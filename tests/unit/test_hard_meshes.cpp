// Hard cases for meshes (ctest label `hard`): slivers of aspect ratio 1:100 and a 1:1000 spread of element
// sizes, with and without selective mass scaling, on a problem with a closed-form answer (the plane-strain
// bulge of a clamped strip under a pressure applied at once, HardCases.hpp) and its regular mesh.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "HardCases.hpp"
#include "structure/integrate/CentralDifference.hpp"

using namespace fsi::structure;
using fsi::test::arcDeflection;
using fsi::test::expectStableRun;
using fsi::test::invertedTriangles;
using fsi::test::kRegularStrip;
using fsi::test::kStripC11t;
using fsi::test::runHard;
using fsi::test::stripScene;

namespace {

// The same 20 × 2 squares on a strip 2 m long: 1 cm × 1 m cells cut into triangles of aspect ratio 100
// (longest edge over smallest altitude).
const std::string kSliverStrip = "{type: rectangle, size: [0.2, 2], center: [0.1, 1, 0], divisions: [20, 2]}";
// Across the strip, one 10 µm element at the clamped edge x = 0, then 20 of 1 cm: sizes 1:1000 (the small one
// is also a 1:1000 sliver, 10 µm × 1 cm).
const std::string kSpreadStrip =
    "{type: strip, path: [[0, 0, 0], [1.0e-5, 0, 0], [0.2, 0, 0]], divisions: [1, 20], width: [0, 0.01, 0]}";
const std::string kSpreadClamped = "[strip/start, strip/end]", kSpreadEnds = "[strip/side0, strip/side1]";

struct Outcome {
  double deflection, lastDt, steps, addedMass;
};

Outcome runStrip(const std::string& name, const std::string& yaml, const std::vector<std::string>& set = {}) {
  Scene s = loadSceneFromString(yaml, name + ".yaml", set);
  const RunResult r = runHard(s, name);
  expectStableRun(r, s);
  EXPECT_EQ(r.reason, StopReason::Static) << name;
  EXPECT_EQ(invertedTriangles(*s.model), 0) << name;
  const auto& st = r.summary["stats"];
  const Outcome o{r.probes.at("deflection"), st["last_dt"].get<double>(), st["steps"].get<double>(),
                  st["added_mass_fraction"].get<double>()};
  std::printf("%-16s deflection %.7g m, %g steps, last dt %.3g s, added mass %.3g\n", name.c_str(),
              o.deflection, o.steps, o.lastDt, o.addedMass);
  return o;
}

}  // namespace

// Slivers: stable means the same static answer as the regular mesh (the y-invariant field is exact on both,
// so the two must agree to the until-static tolerance) and the exact arc within 1e-3, reached at the step the
// altitude allows (no smaller than on the regular mesh: the estimate uses the smallest altitude, not the
// longest edge), with and without selective mass scaling (to twice that step: the static answer must not
// change, the added mass is reported).
TEST(HardMesh, SliversOfAspectRatio100ReachTheRegularMeshAnswer) {
  const double exact = arcDeflection(0.2, kStripC11t, 5000);
  const Outcome regular = runStrip("strip-regular", stripScene(kRegularStrip));
  const Outcome slivers = runStrip("strip-slivers", stripScene(kSliverStrip));
  const Outcome scaled = runStrip("strip-slivers-ms", stripScene(kSliverStrip),
                                  {"time.mass_scaling_min_dt=" + fsi::test::num(2 * slivers.lastDt)});
  EXPECT_NEAR(regular.deflection, exact, 1e-3 * exact);
  EXPECT_NEAR(slivers.deflection, regular.deflection, 1e-5 * exact);
  EXPECT_NEAR(scaled.deflection, regular.deflection, 1e-5 * exact);
  EXPECT_GT(slivers.lastDt, 0.5 * regular.lastDt);
  EXPECT_GT(scaled.addedMass, 0.5);
  EXPECT_GT(scaled.lastDt, 1.5 * slivers.lastDt);
}

// A 1:1000 spread of element sizes: without mass scaling the 10 µm element sets a step ~1000 times smaller
// and the run takes that many more steps, but it must stay stable and reach the same answer; with selective
// mass scaling to the regular mesh's step only the small element gets heavier (by 10⁶: 24 times the strip's
// own mass, all of it on the two nodes 10 µm from the clamp), the step is the regular one, and the static
// answer is unchanged.
TEST(HardMesh, SizeSpreadOf1000ReachesTheAnswerWithAndWithoutMassScaling) {
  const double exact = arcDeflection(0.2, kStripC11t, 5000);
  const Outcome regular = runStrip("spread-regular", stripScene(kRegularStrip));
  const Outcome scaled = runStrip("spread-ms", stripScene(kSpreadStrip, kSpreadClamped, kSpreadEnds),
                                  {"time.mass_scaling_min_dt=" + fsi::test::num(regular.lastDt)});
  const Outcome plain = runStrip("spread-plain", stripScene(kSpreadStrip, kSpreadClamped, kSpreadEnds));
  EXPECT_NEAR(plain.deflection, exact, 2e-3 * exact);
  EXPECT_NEAR(scaled.deflection, plain.deflection, 1e-4 * exact);
  EXPECT_LT(plain.lastDt, 2e-3 * regular.lastDt);
  EXPECT_GT(scaled.lastDt, 0.5 * regular.lastDt);
  EXPECT_GT(scaled.addedMass, 0.0);
}

// The stable-step estimate on slivers: at safety 1 (the step the estimate allows, not less) the sliver strip
// runs stably to the same answer; a fixed step 2.5 times the estimate is an instability, and it must stop
// cleanly as `fsi run` does (exit code 3, a diagnosis naming the element, a finite last good state).
TEST(HardMesh, StableStepEstimateHoldsOnSlivers) {
  const double exact = arcDeflection(0.2, kStripC11t, 5000);
  const Outcome full = runStrip("slivers-safety1", stripScene(kSliverStrip), {"time.safety=1"});
  EXPECT_NEAR(full.deflection, exact, 1e-3 * exact);
  Scene probe = loadSceneFromString(stripScene(kSliverStrip), "slivers.yaml");
  CentralDifference cd(*probe.model, probe.effectList(), probe.constraints, probe.time.integrator);
  cd.evaluateForces(false);
  Scene s = loadSceneFromString(stripScene(kSliverStrip), "slivers.yaml",
                                {"time.fixed_dt=" + fsi::test::num(2.5 * cd.stableDt())});
  const RunResult r = runHard(s, "slivers-unstable");
  EXPECT_EQ(r.exitCode(), 3);
  EXPECT_EQ(r.reason, StopReason::Unstable);
  EXPECT_NE(r.diagnosis.find("triangle"), std::string::npos) << r.diagnosis;
  EXPECT_TRUE(std::filesystem::exists(r.stateFile)) << r.stateFile;
  EXPECT_TRUE(fsi::test::finiteState(*s.model));
}
