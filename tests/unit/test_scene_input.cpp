// Scene input that yaml-cpp accepts but the scene must not: duplicate keys, integers that wrap when narrowed,
// numbers beyond double, text that is not UTF-8, aliases that loop or explode, a second document, selectors
// without their key, probe names the results cannot hold, --set paths into scalars or past a list, and set
// chains. Each one must give a located fsi::InputError (exit code 2 in the CLI), never another exception,
// a crash or a silently different scene.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

#include "TestScenes.hpp"
#include "structure/model/Error.hpp"
#include "structure/scene/Scene.hpp"

using namespace fsi::structure;
using fsi::test::drumScene;

namespace {

// The message of the InputError the scene raises, "" if it loads. Any other exception is a failure of the
// test (it would be exit code 1 or a crash in the CLI), reported as such instead of aborting the test.
std::string errorOf(const std::string& yaml, const std::vector<std::string>& sets = {}) {
  try {
    loadSceneFromString(yaml, "case.yaml", sets);
  } catch (const fsi::InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not an InputError: " << e.what();
    return std::string("not an InputError: ") + e.what();
  }
  return "";
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

const std::string kTime = "time: {end: 0.001}\n";

std::string disc(const std::string& rings) {
  return std::string(R"(materials:
  film: {type: membrane, young: 1.0e8, poisson: 0.3, thickness: 1.0e-3, density: 1000}
meshes:
  disc:
    generator: {type: disc, radius: 1, rings: )") +
         rings + R"(}
    material: film
constraints:
  - {nodes: disc/rim, fix: all}
time: {end: 0.001}
)";
}

}  // namespace

// ---------------------------------------------------------------- duplicate keys

TEST(SceneInput, DuplicateKeyInAFlowMappingIsLocatedWithBothPositions) {
  // yaml-cpp keeps both and a lookup finds the first: this scene used to run at 100 kPa.
  const std::string e =
      errorOf(drumScene("effects:\n  pressure: {triangles: sheet, value: 100.0e3, value: 1.0}\n" + kTime));
  EXPECT_TRUE(has(e, "case.yaml:10:48: effects.pressure.value: duplicate key 'value'")) << e;
  EXPECT_TRUE(has(e, "first at line 10, column 32")) << e;
}

TEST(SceneInput, DuplicateKeyInABlockMappingNamesBothLines) {
  const std::string e = errorOf(drumScene(kTime + "time: {end: 0.5}\n"));
  EXPECT_TRUE(has(e, "case.yaml:10:1: time: duplicate key 'time' (first at line 9, column 1)")) << e;
}

TEST(SceneInput, DuplicateProbeNamesAreALocatedSceneError) {
  // Used to load and fail only in the results writer ("repeats column", exit code 1).
  const std::string e = errorOf(drumScene(kTime + R"(probes:
  tip: {type: displacement, nodes: {nearest: [0, 0, 0]}, component: z}
  tip: {type: displacement, nodes: {nearest: [0.5, 0, 0]}, component: z}
)"));
  EXPECT_TRUE(has(e, "case.yaml:12:3: probes.tip: duplicate key 'tip' (first at line 11, column 3)")) << e;
}

TEST(SceneInput, KeysMustBePlainNames) {
  std::string e = errorOf(drumScene(kTime + "probes: {[a, b]: {type: volume, triangles: sheet}}\n"));
  EXPECT_TRUE(has(e, "case.yaml:10:") && has(e, "probes: a key must be a plain name")) << e;
  e = errorOf(drumScene(kTime + "probes: {: {type: volume, triangles: sheet}}\n"));
  EXPECT_TRUE(has(e, "probes: empty or null key")) << e;
}

// ---------------------------------------------------------------- integers and numbers

TEST(SceneInput, IntegersThatWouldWrapAreOutOfRange) {
  // 4294967297 = 2^32 + 1 used to run as a disc of 1 ring, 4294967300 as a sphere of 4 divisions.
  std::string e = errorOf(disc("4294967297"));
  EXPECT_TRUE(has(e, "case.yaml:5:") && has(e, "meshes.disc.generator.rings: 4294967297 is out of range"))
      << e;
  EXPECT_TRUE(has(e, "2147483647")) << e;
  e = errorOf(disc("16"), {"meshes.disc.generator.rings=4294967297"});
  EXPECT_TRUE(has(e, "meshes.disc.generator.rings: 4294967297 is out of range")) << e;
  e = errorOf(disc("16"), {"meshes.disc.generator={type: sphere_octant, radius: 1, divisions: 4294967300}"});
  EXPECT_TRUE(has(e, "meshes.disc.generator.divisions: 4294967300 is out of range")) << e;
  e = errorOf(drumScene(kTime), {"meshes.sheet.generator.divisions=[8, 4294967304]"});
  EXPECT_TRUE(has(e, "meshes.sheet.generator.divisions[1]: 4294967304 is out of range")) << e;
  // Beyond long, and beyond 2^53 where a double is no longer exact.
  e = errorOf(disc("99999999999999999999999"));
  EXPECT_TRUE(has(e, "rings: 99999999999999999999999 is out of range")) << e;
  e = errorOf(disc("1.0e17"));
  EXPECT_TRUE(has(e, "rings: 1.0e17 is out of range")) << e;
  // An integral number written as a float is still an integer; a fraction is not.
  EXPECT_EQ(errorOf(disc("1.6e1")), "");
  e = errorOf(disc("2.5"));
  EXPECT_TRUE(has(e, "rings: expected an integer, got 2.5")) << e;
}

TEST(SceneInput, IntegerKeysHaveTheirOwnRange) {
  std::string e = errorOf(drumScene("time: {end: 0.001, monitor_every: 0}\n"));
  EXPECT_TRUE(has(e, "time.monitor_every: 0 is out of range; expected an integer >= 1")) << e;
  // 2^64 + 100 used to wrap through the conversion to long.
  e = errorOf(drumScene("time: {end: 0.001, monitor_every: 18446744073709551716}\n"));
  EXPECT_TRUE(has(e, "time.monitor_every: 18446744073709551716 is out of range")) << e;
  e = errorOf(drumScene("solver: {type: dynamic_relaxation, increments: 4294967297}\n"));
  EXPECT_TRUE(
      has(e, "solver.increments: 4294967297 is out of range; expected an integer from 1 to 2147483647"))
      << e;
  e = errorOf(drumScene("solver: {type: dynamic_relaxation, max_iterations: 1.0e30}\n"));
  EXPECT_TRUE(has(e, "solver.max_iterations: 1.0e30 is out of range")) << e;
  e = errorOf(drumScene(kTime + "probes: {p: {type: displacement, nodes: {ids: [1e300], mesh: sheet}, "
                                "component: z}}\n"));
  EXPECT_TRUE(has(e, "probes.p.nodes.ids[0]: 1e300 is out of range")) << e;
}

TEST(SceneInput, NumbersMustBeFiniteDoubles) {
  std::string e = errorOf(drumScene(kTime), {"materials.film.young=1e400"});
  EXPECT_TRUE(has(e, "materials.film.young: 1e400 is out of range")) << e;
  e = errorOf(drumScene("time: {end: .inf}\n"));
  EXPECT_TRUE(has(e, "case.yaml:9:13: time.end: expected a finite number, got '.inf'")) << e;
  e = errorOf(drumScene(kTime + "effects: {pressure: {triangles: sheet, value: .nan}}\n"));
  EXPECT_TRUE(has(e, "effects.pressure.value: expected a finite number, got '.nan'")) << e;
}

// ---------------------------------------------------------------- text

TEST(SceneInput, TextThatIsNotUtf8IsLocated) {
  // Used to run to the end and then fail writing summary.json (json type_error.316), leaving it empty.
  // The whole file is checked first, comments included (found by the fuzz test: a 0xFF in a comment).
  std::string e = errorOf("title: caf\xE9 \xFF\n" + drumScene(kTime));
  EXPECT_TRUE(has(e, "case.yaml:1:11: the file is not valid UTF-8 (byte 0xE9)")) << e;
  e = errorOf(drumScene(kTime + "probes: {\"tip\xC0\xAF\": {type: volume, triangles: sheet}}\n"));
  EXPECT_TRUE(has(e, "case.yaml:10:14: the file is not valid UTF-8 (byte 0xC0)")) << e;
  e = errorOf("# a comment in Latin-1: caf\xE9\n" + drumScene(kTime));
  EXPECT_TRUE(has(e, "case.yaml:1:28: the file is not valid UTF-8 (byte 0xE9)")) << e;
  e = errorOf(drumScene(kTime), {"title=\xED\xA0\x80"});  // an encoded surrogate
  EXPECT_TRUE(has(e, "title: text is not valid UTF-8")) << e;
  // Valid multi-byte text is fine.
  EXPECT_EQ(errorOf("title: \"Fallschirm \xC3\xBC \xE2\x88\x86r \xF0\x9F\xAA\x82\"\n" + drumScene(kTime)),
            "");
}

TEST(SceneInput, ProbeNamesTheResultsCannotHoldAreRefused) {
  // 'time' is the first column of /tables/probes: used to fail in the results writer after the run.
  for (const std::string name : {"time", "a/b", "\"tab\\tname\""}) {
    const std::string e =
        errorOf(drumScene(kTime + "probes:\n  " + name + ": {type: volume, triangles: sheet}\n"));
    EXPECT_TRUE(has(e, "case.yaml:11:") && has(e, "cannot name a probe")) << name << ": " << e;
  }
}

// ---------------------------------------------------------------- document structure

TEST(SceneInput, ASecondDocumentIsAnErrorNotIgnored) {
  // yaml-cpp's Load() reads the first document only: the effects below were silently dropped.
  const std::string e =
      errorOf(drumScene(kTime + "---\neffects: {pressure: {triangles: sheet, value: 1}}\n"));
  EXPECT_TRUE(has(e, "case.yaml:11:1:") && has(e, "a second YAML document")) << e;
  EXPECT_EQ(errorOf(drumScene(kTime + "...\n")), "");  // an explicit end with nothing after it is fine
}

TEST(SceneInput, AnAliasThatContainsItselfIsACycleNotACrash) {
  // Used to recurse without end in the selector resolution (stack overflow).
  const std::string e =
      errorOf(drumScene(kTime + "probes: {p: {type: volume, triangles: &t [sheet, *t]}}\n"));
  EXPECT_TRUE(has(e, "case.yaml:10:") &&
              has(e, "probes.p.triangles[1]: an alias refers to a node that contains it"))
      << e;
}

TEST(SceneInput, AliasesThatExpandExponentiallyAreRefusedQuickly) {
  std::string yaml = drumScene(kTime) + "sets:\n  a0: &a0 [sheet/boundary, sheet/xmin]\n";
  for (int k = 1; k <= 30; ++k)
    yaml += "  a" + std::to_string(k) + ": &a" + std::to_string(k) + " [*a" + std::to_string(k - 1) + ", *a" +
            std::to_string(k - 1) + "]\n";
  const auto start = std::chrono::steady_clock::now();
  const std::string e = errorOf(yaml);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  EXPECT_TRUE(has(e, "expands to more than")) << e;
}

TEST(SceneInput, NestingIsLimitedAlsoThroughAliases) {
  // yaml-cpp stops plain nesting at about 500 levels (with the message "bad file").
  std::string e = errorOf(drumScene(kTime + "probes: {p: {type: volume, triangles: " + std::string(600, '[') +
                                    "sheet" + std::string(600, ']') + "}}\n"));
  EXPECT_TRUE(has(e, "case.yaml:10:") && has(e, "nested too deeply")) << e;
  // Anchors 100 levels deep, each inside the next: 40000 levels used to overflow the stack of the set reader.
  std::string yaml = drumScene(kTime) + "sets:\n";
  std::string previous = "sheet";
  for (int k = 0; k < 400; ++k) {
    yaml += "  n" + std::to_string(k) + ": &n" + std::to_string(k) + " " + std::string(100, '[') + previous +
            std::string(100, ']') + "\n";
    previous = "*n" + std::to_string(k);
  }
  e = errorOf(yaml);
  EXPECT_TRUE(has(e, "case.yaml:") && has(e, "sets.n4") && has(e, "nested more than 500 levels deep")) << e;
}

// ---------------------------------------------------------------- selectors and sets

TEST(SceneInput, ProbeOrEffectWithoutItsSelectorIsLocated) {
  // Used to escape as yaml-cpp's InvalidNode ("invalid node; first invalid key: \"nodes\"", exit code 1).
  std::string e = errorOf(drumScene(kTime + "probes:\n  tip: {type: displacement, component: z}\n"));
  EXPECT_TRUE(has(e, "case.yaml:11:8: probes.tip: missing required key 'nodes'")) << e;
  e = errorOf(drumScene(kTime + "probes:\n  v: {type: volume}\n"));
  EXPECT_TRUE(has(e, "probes.v: missing required key 'triangles'")) << e;
  e = errorOf(drumScene(kTime + "effects:\n  pressure: {value: 100}\n"));
  EXPECT_TRUE(has(e, "case.yaml:11:13: effects.pressure: missing required key 'triangles'")) << e;
  e = errorOf(drumScene(kTime + "effects:\n  nodal_forces: [{force: [0, 0, 1]}]\n"));
  EXPECT_TRUE(has(e, "effects.nodal_forces[0]: missing required key 'nodes'")) << e;
  e = errorOf(drumScene(kTime), {"constraints.0={fix: all}"});
  EXPECT_TRUE(has(e, "constraints[0]: missing required key 'nodes'")) << e;
}

TEST(SceneInput, AnEmptyValueIsLocatedAtItsKey) {
  // `tip:` with nothing after it is a null node without a place in the file; the message used to say only
  // "case.yaml: probes.tip: ..." (found by the fuzz test).
  const std::string e = errorOf(drumScene(kTime + "probes:\n  tip:\n"));
  EXPECT_TRUE(has(e, "case.yaml:11:3: probes.tip: missing required key 'type'")) << e;
  const std::string f = errorOf(drumScene(kTime + "probes:\n  tip:\n    type: displacement\n    nodes:\n"));
  EXPECT_TRUE(has(f, "case.yaml:13:5: probes.tip.nodes: no value given")) << f;
}

TEST(SceneInput, SubnormalDensityOrOutputIntervalIsRefused) {
  // density 1e-320 passed "> 0", the lumped masses underflowed to 0 and the run blamed a node for belonging
  // to no element; an output interval of 1e-320 s made every step an output (fuzz findings).
  std::string e = errorOf(drumScene(kTime), {"materials.film.density=1.0e-320"});
  EXPECT_TRUE(has(e, "materials.film.density: must be > 0 and at least 2.2e-308")) << e;
  e = errorOf(drumScene(kTime + "output: {interval: 1.0e-320}\n"));
  EXPECT_TRUE(has(e, "output.interval: must be 0 (every step) or at least 2.2e-308")) << e;
  EXPECT_EQ(errorOf(drumScene(kTime), {"materials.film.density=1.0e-300"}), "");
}

TEST(SceneInput, AChainOfSetsIsNotACycle) {
  // set_k = set_{k-1} plus node k+1: 22 sets deep used to be reported as a cycle.
  std::string yaml = drumScene(kTime) + "sets:\n  set0: {ids: [1], mesh: sheet}\n";
  for (int k = 1; k < 22; ++k)
    yaml += "  set" + std::to_string(k) + ": [set" + std::to_string(k - 1) + ", {ids: [" +
            std::to_string(k + 1) + "], mesh: sheet}]\n";
  yaml += "probes: {p: {type: displacement, nodes: set21, component: z, reduce: mean}}\n";
  Scene s;
  ASSERT_NO_THROW(s = loadSceneFromString(yaml, "case.yaml")) << errorOf(yaml);
  // The same 22 nodes selected directly.
  std::string ids;
  for (int k = 1; k <= 22; ++k) ids += (k > 1 ? ", " : "") + std::to_string(k);
  const Scene direct =
      loadSceneFromString(drumScene(kTime) + "probes: {p: {type: displacement, nodes: {ids: [" + ids +
                              "], mesh: sheet}, component: z, reduce: mean}}\n",
                          "case.yaml");
  EXPECT_EQ(s.probes.at(0).nodes.size(), 22u);
  EXPECT_EQ(s.probes.at(0).nodes, direct.probes.at(0).nodes);
  // Sets that double each other: each is resolved once, so 40 levels are cheap.
  yaml = drumScene(kTime) + "sets:\n  d0: [sheet/xmin]\n";
  for (int k = 1; k <= 40; ++k)
    yaml +=
        "  d" + std::to_string(k) + ": [d" + std::to_string(k - 1) + ", d" + std::to_string(k - 1) + "]\n";
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(errorOf(yaml), "");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

TEST(SceneInput, ARealCycleOfSetsNamesItsMembers) {
  std::string e = errorOf(drumScene(kTime + "sets:\n  a: [sheet/xmin, b]\n  b: [c]\n  c: a\n"));
  EXPECT_TRUE(has(e, "sets refer to each other in a cycle: a -> b -> c -> a")) << e;
  EXPECT_TRUE(has(e, "case.yaml:13:6: sets.c")) << e;
  e = errorOf(drumScene(kTime + "sets:\n  self: [sheet/xmin, self]\n"));
  EXPECT_TRUE(has(e, "cycle: self -> self")) << e;
  // As a triangle selector too.
  e = errorOf(drumScene(kTime + "sets:\n  p: q\n  q: p\neffects: {pressure: {triangles: p, value: 1}}\n"));
  EXPECT_TRUE(has(e, "cycle: p -> q -> p")) << e;
}

// ---------------------------------------------------------------- --set

TEST(SceneInput, SetIntoAScalarOrPastAListIsAnInputError) {
  // Both used to escape as std::invalid_argument / out_of_range or a yaml-cpp exception (exit code 1).
  std::string e = errorOf(drumScene(kTime), {"time.end.x=1"});
  EXPECT_TRUE(
      has(e, "--set 'time.end.x=1': 'time.end' is a value ('0.001'), not a mapping, so it has no key 'x'"))
      << e;
  e = errorOf(drumScene(kTime), {"constraints.12345678901234567890123.fix=x"});
  EXPECT_TRUE(has(e, "index 12345678901234567890123 is out of range; 'constraints' has indices 0 to 0")) << e;
  e = errorOf(drumScene(kTime), {"constraints.1=x"});
  EXPECT_TRUE(has(e, "index 1 is out of range")) << e;
  e = errorOf(drumScene(kTime), {"constraints.first.fix=x"});
  EXPECT_TRUE(has(e, "'constraints' is a list, so 'first' must be an index")) << e;
  e = errorOf(drumScene(kTime), {"time..end=1"});
  EXPECT_TRUE(has(e, "--set 'time..end=1': empty key")) << e;
  e = errorOf(drumScene(kTime), {"time.end=[1"});
  EXPECT_TRUE(has(e, "--set 'time.end=[1': the value is not valid YAML")) << e;
  e = errorOf("5\n", {"time.end=1"});
  EXPECT_TRUE(has(e, "'(top level)' is a value ('5')")) << e;
  // A value from --set is checked like the file: duplicate keys, UTF-8.
  e = errorOf(drumScene(kTime), {"time={end: 1, end: 2}"});
  EXPECT_TRUE(has(e, "time.end: duplicate key 'end'")) << e;
}

// ---------------------------------------------------------------- one rule for positive values, YAML types

TEST(SceneInput, EveryPositiveValueRefusesSubnormals) {
  // thickness 1.0e-320 passed "> 0" while density 1.0e-320 was refused; the run then died as "unstable"
  // (issue 35, item 11). One rule (isPositiveNormal) for every quantity that must be > 0.
  for (const std::string set : {"materials.film.thickness=1.0e-320", "materials.film.young=4.9e-324",
                                "time.max_dt=1.0e-320", "time.energy_tolerance=1.0e-320"}) {
    const std::string e = errorOf(drumScene(kTime), {set});
    const std::string key = set.substr(0, set.find('='));
    EXPECT_TRUE(has(e, key + ": must be > 0 and at least 2.2e-308")) << set << ": " << e;
  }
  EXPECT_EQ(errorOf(drumScene(kTime), {"materials.film.thickness=1.0e-300"}), "");
}

TEST(SceneInput, QuotedOrStrTaggedNumbersAreRefused) {
  // "1e8" and !!str 1e8 are strings in YAML; they were read as numbers (issue 35, item 11).
  std::string e = errorOf(drumScene(kTime), {"materials.film.young=\"1.0e8\""});
  EXPECT_TRUE(
      has(e, "case.yaml:1:1: materials.film.young: expected a number, got the string '1.0e8' (quoted)"))
      << e;
  e = errorOf(drumScene(kTime), {"materials.film.young=!!str 1.0e8"});
  EXPECT_TRUE(has(e, "materials.film.young: expected a number, got the string '1.0e8' (tagged !!str)")) << e;
  e = errorOf(drumScene("time: {end: '0.001'}\n"));
  EXPECT_TRUE(has(e, "case.yaml:9:13: time.end: expected a number")) << e;
  e = errorOf(drumScene(kTime), {"meshes.sheet.generator.divisions=[8, \"8\"]"});
  EXPECT_TRUE(has(e, "meshes.sheet.generator.divisions[1]: expected an integer, got the string '8'")) << e;
  e = errorOf(drumScene(kTime), {"materials.film.wrinkling=\"false\""});
  EXPECT_TRUE(has(e, "materials.film.wrinkling: expected true or false, got the string 'false'")) << e;
  // The core tags that match the key are honoured; a quoted name is still a name.
  EXPECT_EQ(
      errorOf(drumScene(kTime), {"materials.film.young=!!float 1.0e8", "meshes.sheet.material=\"film\""}),
      "");
}

TEST(SceneInput, TagsOtherThanTheMatchingCoreOnesAreRefused) {
  std::string e = errorOf(drumScene(kTime), {"constraints.0.fix=!foo all"});
  EXPECT_TRUE(has(e, "constraints[0].fix: the tag '!foo' is not supported")) << e;
  e = errorOf(drumScene(kTime), {"materials.film.young=!!int 1.5"});
  EXPECT_TRUE(has(e, "materials.film.young: '1.5' is tagged !!int but is not an integer")) << e;
  e = errorOf(drumScene("time: {end: !!null 5}\n"));
  EXPECT_TRUE(has(e, "case.yaml:9:13: time.end: '5' is tagged !!null, which is no value")) << e;
  e = errorOf(drumScene("time: {end: !!binary AAAA}\n"));
  EXPECT_TRUE(has(e, "case.yaml:9:13: time.end: the tag '!!binary' is not supported")) << e;
  e = errorOf(drumScene(kTime), {"title=!!int 5"});
  EXPECT_TRUE(has(e, "title: expected a string, but '5' is tagged !!int")) << e;
}

TEST(SceneInput, NullValuesAreLocated) {
  // `thickness: !!null` is no value (it was read as an empty number); `--set key=` named neither the --set
  // nor a line; a null list entry became an empty constraint or selector without a place in the file.
  std::string e = errorOf(drumScene(kTime), {"time.end="});
  EXPECT_TRUE(has(e, "--set 'time.end=': no value after '='")) << e;
  e = errorOf(drumScene(kTime), {"time.end=~"});
  EXPECT_TRUE(has(e, "--set 'time.end=~': no value after '='")) << e;
  e = errorOf(drumScene("time: {end: !!null }\n"));
  EXPECT_TRUE(has(e, "case.yaml:9:8: time.end: no value given")) << e;
  e = errorOf(drumScene("  - null\n" + kTime));
  EXPECT_TRUE(has(e, "case.yaml:9:5: constraints[1]: a list entry has no value (empty or null)")) << e;
  e = errorOf(drumScene("  - nodes:\n      - sheet/boundary\n      - null\n    fix: all\n" + kTime));
  EXPECT_TRUE(has(e, "case.yaml:11:9: constraints[1].nodes[1]: a list entry has no value")) << e;
}
