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
// The other orientation: 1 cm × 0.1 mm cells, the long edges along the bulge (across the strip), so the
// smallest altitude (0.1 mm) sets a step 100 times smaller than the regular mesh's.
const std::string kSliverAcross =
    "{type: rectangle, size: [0.2, 2.0e-4], center: [0.1, 1.0e-4, 0], divisions: [20, 2]}";
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

// Slivers: stable means the same static answer as the regular mesh (the y-invariant field is exact on all of
// them, so they must agree to the until-static tolerance) and the exact arc within 1e-3, reached at the step
// the smallest altitude allows: with the long edges along the strip that is no smaller than on the regular
// mesh (the estimate uses the altitude, not the longest edge); with the long edges across it, 100 times
// smaller. With selective mass scaling (to twice the first one's step; to the regular mesh's step for the
// second, 4,800 times the mass) the static answer must not change and the added mass is reported. (When every
// element is a sliver, scaling them all alike slows every mode as much as it lengthens the step: the second
// takes as many steps scaled as unscaled. Mass scaling pays where a few elements limit the step, as in the
// size-spread test below.)
TEST(HardMesh, SliversOfAspectRatio100ReachTheRegularMeshAnswer) {
  const double exact = arcDeflection(0.2, kStripC11t, 5000);
  const Outcome regular = runStrip("strip-regular", stripScene(kRegularStrip));
  const Outcome slivers = runStrip("strip-slivers", stripScene(kSliverStrip));
  const Outcome scaled = runStrip("strip-slivers-ms", stripScene(kSliverStrip),
                                  {"time.mass_scaling_min_dt=" + fsi::test::num(2 * slivers.lastDt)});
  const Outcome across = runStrip("strip-across", stripScene(kSliverAcross));
  // Scaling every element's density by s slows every mode by √s: the mass damping keeps its damping ratio
  // with α/√s (at 1500 /s the scaled run is overdamped 70 times and creeps), and it needs √s times the
  // simulated time (not more steps).
  const double alphaScaled = 1500 * across.lastDt / regular.lastDt;
  const Outcome acrossScaled = runStrip(
      "strip-across-ms", stripScene(kSliverAcross),
      {"time.mass_scaling_min_dt=" + fsi::test::num(regular.lastDt),
       "effects.mass_damping.alpha=" + fsi::test::num(alphaScaled), "time.until_static.max_time=100"});
  EXPECT_NEAR(regular.deflection, exact, 1e-3 * exact);
  for (const Outcome* o : {&slivers, &scaled, &across, &acrossScaled})
    EXPECT_NEAR(o->deflection, regular.deflection, 1e-5 * exact);
  EXPECT_GT(slivers.lastDt, 0.5 * regular.lastDt);
  EXPECT_GT(scaled.addedMass, 0.5);
  EXPECT_GT(scaled.lastDt, 1.5 * slivers.lastDt);
  EXPECT_LT(across.lastDt, 0.02 * regular.lastDt);
  EXPECT_GT(acrossScaled.lastDt, 0.5 * regular.lastDt);
  EXPECT_GT(acrossScaled.addedMass, 10.0);
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
// cleanly as `fsi run` does (exit code 3, a diagnosis naming the element and the remedy, a smaller
// time.fixed_dt, and a finite last good state).
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
  EXPECT_NE(r.diagnosis.find("a smaller time.fixed_dt helps"), std::string::npos) << r.diagnosis;
  EXPECT_TRUE(std::filesystem::exists(r.stateFile)) << r.stateFile;
  EXPECT_TRUE(fsi::test::finiteState(*s.model));
}
