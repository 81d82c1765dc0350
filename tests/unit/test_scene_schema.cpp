// The declared scene schema (structure/scene/SceneSchema, model/SchemaKey): the readers check types and
// ranges through their sections' entries, with the entry's message at the key's line; unknown keys get a
// "did you mean" from the section's names; every default is valid under its own entry; docs/SCENES.md's key
// reference is the schema's (a missing, extra or changed row fails); buildModel's errors about one mesh are
// put at that mesh's entry by its index, not by searching the message.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "TestScenes.hpp"
#include "coupling/effects/CouplingEffects.hpp"
#include "structure/elements/BuildModel.hpp"
#include "structure/model/Error.hpp"
#include "structure/model/MaterialKeys.hpp"
#include "structure/parafoil/ParafoilScene.hpp"
#include "structure/scene/ReadControls.hpp"
#include "structure/scene/Scene.hpp"
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/effects/EffectKinds.hpp"
#include "structure/scene/kinds/KindReaders.hpp"

using namespace fsi::structure;
using fsi::test::drumScene;
namespace fs = std::filesystem;

namespace {

const std::string kTime = "time: {end: 0.01}\n";  // line 9 after the 8 lines of drumScene

std::string errorOf(const std::string& yaml) {
  return fsi::test::sceneError(yaml, "case.yaml");
}

bool has(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

std::string scenesDoc() {
  std::ifstream is(std::string(FSI_SOURCE_DIR) + "/docs/SCENES.md");
  std::stringstream ss;
  ss << is.rdbuf();
  return ss.str();
}

// A parafoil scene (the generator entry on line 6).
std::string wingScene(const std::string& extra) {
  return "materials:\n"
         "  fabric: {type: membrane, young: 1.0e9, poisson: 0.3, thickness: 1.0e-4, density: 1000}\n"
         "  line: {type: cable, young: 4.3e10, area: 3.0e-6, density: 906}\n"
         "meshes:\n"
         "  wing:\n"
         "    generator: {type: parafoil, cells: 4, chordwise_points: 12, span_divisions: 1, brake_points: "
         "2" +
         extra +
         "}\n"
         "    material: fabric\n"
         "    cable_material: line\n"
         "constraints:\n"
         "  - {nodes: wing/confluence, fix: all}\n"
         "time: {end: 1.0e-4}\n";
}

}  // namespace

TEST(SceneSchemaRead, RangeErrorsComeFromTheEntry) {
  // The message is the entry's (its range text), at the key's line and column.
  std::string e = errorOf(fsi::test::replaced(drumScene(kTime), "poisson: 0.3", "poisson: 0.6"));
  EXPECT_TRUE(has(e, "case.yaml:2:") && has(e, "materials.film.poisson: is 0.6; valid: " +
                                                   membraneMaterialKeys().key("poisson").rangeText()))
      << e;
  EXPECT_EQ(membraneMaterialKeys().key("poisson").rangeText(), "[0, 0.5)");

  e = errorOf(drumScene("time: {end: 0.01, safety: 1.5}\n"));
  EXPECT_TRUE(has(e, "case.yaml:9:") && has(e, "time.safety: is 1.5; valid: (0, 1]")) << e;

  e = errorOf(wingScene(", thickness_scale: 6"));
  EXPECT_TRUE(has(e, "case.yaml:6:") && has(e, "meshes.wing.generator.thickness_scale: is 6; valid: (0, 5]"))
      << e;

  // An integer's range from the entry too.
  e = errorOf(drumScene(kTime + "solver: {threads: 2000}\n"));
  EXPECT_TRUE(has(e, "solver.threads: 2000 is out of range; expected an integer from 1 to 1024")) << e;

  // A positive quantity under the one rule, from the entry of `density`.
  e = errorOf(fsi::test::replaced(drumScene(kTime), "density: 1000", "density: 1.0e-320"));
  EXPECT_TRUE(has(e, "materials.film.density: must be > 0 and at least 2.2e-308")) << e;

  // A list's entries each under the range.
  e = errorOf(wingScene(", rows: [0.1, 0.5, 1.2]"));
  EXPECT_TRUE(has(e, "meshes.wing.generator.rows: entry 2: is 1.2; valid: (0, 1)")) << e;
}

TEST(SceneSchemaRead, MaterialCheckedOnceWithOneMessage) {
  // The model builder's guard of a material made in code is the same entry's check and message.
  MembraneMaterial m{"film", 1e8, 0.6, 1e-3, 1000, true};
  try {
    checkMaterial(m);
    FAIL() << "poisson 0.6 accepted";
  } catch (const fsi::InputError& e) {
    EXPECT_STREQ(e.what(), "material 'film': poisson is 0.6; valid: [0, 0.5)");
  }
  EXPECT_THROW(checkMaterial(PointMassMaterial{"payload", 0.0}), fsi::InputError);
  EXPECT_THROW(checkMaterial(CableMaterial{"rope", 1e9, -1, 1000}), fsi::InputError);
  EXPECT_NO_THROW(checkMaterial(CableMaterial{"rope", 1e9, 1e-4, 1000}));
}

TEST(SceneSchemaRead, WrongTypeIsNamed) {
  std::string e = errorOf(fsi::test::replaced(drumScene(kTime), "young: 1.0e8", "young: \"1.0e8\""));
  EXPECT_TRUE(has(e, "materials.film.young: expected a number, got the string '1.0e8'")) << e;
  e = errorOf(drumScene(kTime + "solver: {threads: 1.5}\n"));
  EXPECT_TRUE(has(e, "case.yaml:10:") && has(e, "solver.threads: expected an integer, got 1.5")) << e;
  e = errorOf(wingScene(", trailing_edge_tape: 3"));
  EXPECT_TRUE(has(e, "meshes.wing.generator.trailing_edge_tape: expected true or false")) << e;
  e = errorOf(wingScene(", chordwise_spacing: cosin"));
  EXPECT_TRUE(has(e, "'cosin' is not valid (did you mean 'cosine'?); valid choices: cosine, half_cosine"))
      << e;
}

// The element kinds' keys of a mesh entry are declared by their readers (scene/kinds) with a real type, and
// the mesh entry's section is where the mesh comes from followed by exactly those keys.
TEST(SceneSchemaRead, KindKeysAreDeclaredWithTheirTypes) {
  std::vector<std::string> expected{"file", "generator"};
  for (const KindReader& r : kindReaders()) {
    ASSERT_NE(r.schema, nullptr) << r.kind;
    for (const SceneKey& k : r.schema->keys) {
      EXPECT_NE(k.type, KeyType::Any) << r.kind << "." << k.name;
      EXPECT_FALSE(k.description.empty()) << r.kind << "." << k.name;
      EXPECT_FALSE(k.defaultValue.empty() && k.defaultNote.empty()) << r.kind << "." << k.name;
      expected.push_back(k.name);
    }
  }
  EXPECT_EQ(meshEntrySchema().names(), expected);
  for (const SceneKey& k : meshEntrySchema().keys) EXPECT_NE(k.type, KeyType::Any) << k.name;
  EXPECT_EQ(meshEntrySchema().key("bar_material").type, KeyType::String);
  EXPECT_EQ(meshEntrySchema().key("cables").type, KeyType::Strings);
  EXPECT_EQ(meshEntrySchema().key("point_masses").type, KeyType::Map);
}

TEST(SceneSchemaRead, KindKeysWrongTypeLocatedAtTheKey) {
  // line 7, after `material: film` (line 6) of the drum's mesh entry
  std::string e =
      errorOf(fsi::test::replaced(drumScene(kTime), "    material: film\n",
                                  "    material: film\n    bars: all\n    bar_material: {a: 1}\n"));
  EXPECT_TRUE(has(e, "case.yaml:8:") && has(e, "meshes.sheet.bar_material: expected a string")) << e;
  e = errorOf(fsi::test::replaced(drumScene(kTime), "    material: film\n",
                                  "    material: film\n    cables: {a: 1}\n"));
  EXPECT_TRUE(has(e, "case.yaml:7:") && has(e, "meshes.sheet.cables: expected a string or a list of strings"))
      << e;
  e = errorOf(fsi::test::replaced(drumScene(kTime), "    material: film\n",
                                  "    material: film\n    point_masses: [a]\n"));
  EXPECT_TRUE(has(e, "case.yaml:7:") && has(e, "meshes.sheet.point_masses")) << e;
}

// The sections that were described only in docs/SCENES.md's text: sets, the selectors' mapping forms, the
// extrude constraint, the chordwise_pressure and pressure_field effects; their readers' valid keys are the
// sections' names.
TEST(SceneSchemaRead, SetsSelectorsExtrudeAndPressureTablesAreDeclared) {
  fsi::coupling::registerCouplingEffects();
  std::set<std::string> paths;
  for (const SchemaSection* s : sceneSchema()) EXPECT_TRUE(paths.insert(s->path).second) << s->path;
  for (const char* p : {"sets", "selector {plane: ...}", "selector {box: ...}", "selector {nearest: ...}",
                        "selector {ids: ...}", "constraints[i].extrude", "effects.chordwise_pressure",
                        "effects.pressure_field"})
    EXPECT_TRUE(paths.count(p)) << p;
  for (const EffectKind& k : effectKinds()) EXPECT_NE(k.schema, nullptr) << k.name;

  std::string e = errorOf(drumScene(kTime + "sets: {corner: {box: {min: [0, 0, 0], max: [0.1, 0.1, 0]}, "
                                            "amog: sheet}}\n"));
  EXPECT_TRUE(has(e, "case.yaml:10:") && has(e, "unknown key 'amog' (did you mean 'among'?)")) << e;
  e = errorOf(drumScene(kTime + "sets: {c: {nearest: [0, 0, 0], tolerance: 1}}\n"));
  EXPECT_TRUE(has(e, "sets.c.tolerance: unknown key 'tolerance'")) << e;
  e = errorOf(
      fsi::test::replaced(drumScene(kTime), "  - {nodes: sheet/boundary, fix: all}\n",
                          "  - {nodes: sheet, extrude: {direction: [0, 0, 1], hold: true, tolerace: 1}}\n"));
  EXPECT_TRUE(has(e, "constraints[0].extrude.tolerace: unknown key 'tolerace' (did you mean 'tolerance'?)"))
      << e;
}

TEST(SceneSchemaRead, UnknownKeyGetsDidYouMeanFromTheSection) {
  std::string e = errorOf(wingScene(", spn: 3"));
  EXPECT_TRUE(has(e, "case.yaml:6:") && has(e, "unknown key 'spn' (did you mean 'span'?)")) << e;
  for (const std::string& k : parafoil::parafoilSchema().names()) EXPECT_TRUE(has(e, k)) << k << ": " << e;

  e = errorOf(fsi::test::replaced(drumScene(kTime), "poisson: 0.3", "poisson: 0.3, wrinklng: false"));
  EXPECT_TRUE(has(e, "materials.film.wrinklng: unknown key 'wrinklng' (did you mean 'wrinkling'?)")) << e;

  e = errorOf(drumScene("time: {end: 0.01, monitor_evry: 10}\n"));
  EXPECT_TRUE(has(e, "unknown key 'monitor_evry' (did you mean 'monitor_every'?)")) << e;

  e = errorOf(drumScene(kTime + "probes: {c: {type: displacement, nodes: {nearest: [0.5, 0.5, 0]}, "
                                "component: z, centre: [0, 0, 0]}}\n"));
  EXPECT_TRUE(has(e, "probes.c.centre: unknown key 'centre' (did you mean 'center'?)")) << e;
}

TEST(SceneSchemaRead, DefaultsAreValidUnderTheirOwnEntries) {
  for (const SchemaSection* s : sceneSchema()) {
    for (const SceneKey& k : s->keys) {
      if (k.defaultValue.empty()) continue;
      if (k.type == KeyType::Number || k.type == KeyType::Integer) {
        EXPECT_TRUE(k.inRange(std::stod(k.defaultValue))) << s->path << "." << k.name;
      } else if (k.type == KeyType::Choice) {
        EXPECT_NE(std::find(k.choices.begin(), k.choices.end(), k.defaultValue), k.choices.end())
            << s->path << "." << k.name;
      } else if (k.type == KeyType::Boolean) {
        EXPECT_TRUE(k.defaultValue == "true" || k.defaultValue == "false") << s->path << "." << k.name;
      }
    }
  }
}

TEST(SceneSchemaRead, ParafoilDefaultsAreTheParameters) {
  // The scene's defaults are the schema's; they must build what ParafoilParams{} builds.
  const std::string yaml = "{type: parafoil}";
  const YAML::Node n = YAML::Load(yaml);
  const YamlMap g(n, "x.yaml", "g");
  g.raw("type");  // read by generateMesh
  const parafoil::ParafoilParams fromScene = parafoil::readParafoilParams(g, ".");
  const parafoil::ParafoilParams plain;
  EXPECT_EQ(fromScene.span, plain.span);
  EXPECT_EQ(fromScene.rootChord, plain.rootChord);
  EXPECT_EQ(fromScene.cells, plain.cells);
  EXPECT_EQ(fromScene.arcRadius, plain.arcRadius);
  EXPECT_EQ(fromScene.chordwisePoints, plain.chordwisePoints);
  EXPECT_EQ(fromScene.spanDivisions, plain.spanDivisions);
  EXPECT_EQ(fromScene.rows, plain.rows);
  EXPECT_EQ(fromScene.cascade, plain.cascade);
  EXPECT_EQ(fromScene.cascadeFraction, plain.cascadeFraction);
  EXPECT_EQ(fromScene.lineLength, plain.lineLength);
  EXPECT_EQ(fromScene.riggingDeg, plain.riggingDeg);
  EXPECT_EQ(fromScene.lineElements, plain.lineElements);
  EXPECT_EQ(fromScene.brakePoints, plain.brakePoints);
  EXPECT_EQ(fromScene.toggleFraction, plain.toggleFraction);
  EXPECT_EQ(fromScene.brakeSlack, plain.brakeSlack);
  EXPECT_EQ(fromScene.bulge, plain.bulge);
  EXPECT_EQ(fromScene.trailingEdgeTape, plain.trailingEdgeTape);
  EXPECT_FALSE(fromScene.tipChord || fromScene.riserLength || fromScene.rowTrim);
}

TEST(SceneSchemaDocs, DocsHoldTheSchema) {
  // The coupling library's pressure_field is in the schema once registered (as `fsi` does at start).
  fsi::coupling::registerCouplingEffects();
  const std::vector<std::string> problems = schemaDocsProblems(scenesDoc());
  std::string all;
  for (const auto& p : problems) all += p + "\n";
  EXPECT_TRUE(problems.empty()) << all << "docs/SCENES.md should have, between its markers:\n"
                                << schemaMarkdown();
}

TEST(SceneSchemaDocs, MissingExtraOrChangedRowsFail) {
  fsi::coupling::registerCouplingEffects();
  const std::string doc = scenesDoc();
  const SceneKey& safety = timeSchema().key("safety");
  const std::string row = "| `safety` | number | " + safety.defaultText() + " | " + safety.rangeText();
  const auto at = doc.find(row);
  ASSERT_NE(at, std::string::npos) << row;
  const auto eol = doc.find('\n', at);

  // A schema key missing from the docs.
  std::string missing = doc;
  missing.erase(at, eol - at + 1);
  std::vector<std::string> p = schemaDocsProblems(missing);
  ASSERT_FALSE(p.empty());
  EXPECT_EQ(p.front(), "section 'time': key 'safety' is in the schema but not in docs/SCENES.md");

  // A documented key the schema lacks.
  std::string extra = doc;
  extra.insert(eol + 1, "| `saftey` | number | 0.9 | (0, 1] | - | typo |\n");
  p = schemaDocsProblems(extra);
  ASSERT_FALSE(p.empty());
  EXPECT_EQ(p.front(), "section 'time': key 'saftey' is in docs/SCENES.md but not in the schema");

  // A default that differs.
  std::string changed = doc;
  changed.replace(at, row.size(), "| `safety` | number | 0.8 | " + safety.rangeText());
  p = schemaDocsProblems(changed);
  ASSERT_FALSE(p.empty());
  EXPECT_TRUE(has(p.front(), "section 'time': key 'safety': docs/SCENES.md has")) << p.front();

  // No key reference at all.
  p = schemaDocsProblems("# Scene files\n");
  ASSERT_EQ(p.size(), 1u);
  EXPECT_TRUE(has(p.front(), "no key reference")) << p.front();
}

TEST(SceneSchemaMeshErrors, LocatedAtTheMeshByIndex) {
  // A degenerate triangle in the second of two meshes: the message is put at that mesh's entry (its file,
  // and the entry's line), from the index the builder's error carries.
  const fs::path dir = fs::temp_directory_path() / "fsi_scene_schema_mesh_error";
  fs::create_directories(dir);
  std::ofstream(dir / "bad.msh") << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n"
                                    "3 0 1 0\n4 1 0 0\n$EndNodes\n$Elements\n2\n1 2 2 1 1 1 2 3\n"
                                    "2 2 2 1 1 1 2 4\n$EndElements\n";
  const std::string yaml =
      fsi::test::replaced(drumScene(kTime), "    material: film\n",
                          "    material: film\n  sheet2:\n    file: bad.msh\n    material: film\n");
  std::ofstream(dir / "case.yaml") << yaml;
  try {
    loadScene(dir / "case.yaml");
    FAIL() << "degenerate element accepted";
  } catch (const fsi::InputError& e) {
    const std::string m = e.what();
    EXPECT_TRUE(has(m, "bad.msh (") && has(m, "case.yaml:8:5: meshes.sheet2)") && has(m, "meshes.sheet2)"))
        << m;
    EXPECT_TRUE(has(m, "triangle 2 of mesh 'sheet2' is degenerate")) << m;
  }

  // The builder's error names the mesh by index.
  MeshInput in;
  in.mesh.name = "loose";
  in.mesh.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  in.mesh.triangles = {{0, 1, 2}};
  try {
    buildModel({MeshInput{}, in}, MaterialTable{});
    FAIL() << "a mesh with triangles and no material accepted";
  } catch (const fsi::MeshInputError& e) {
    EXPECT_EQ(e.mesh(), 1);
  }
}
