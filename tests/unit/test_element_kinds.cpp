// The element-kind and material-type registries: consistent names, and every kind's share of the model.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <string>

#include "TestScenes.hpp"
#include "structure/elements/BuildModel.hpp"
#include "structure/elements/ElementKind.hpp"
#include "structure/elements/PointMassElement.hpp"
#include "structure/model/Error.hpp"
#include "structure/scene/Generators.hpp"
#include "structure/scene/MaterialTypes.hpp"
#include "structure/scene/Scene.hpp"
#include "structure/scene/kinds/KindReaders.hpp"

using namespace fsi::structure;
using fsi::test::sceneError;

TEST(ElementKinds, RegistryNamesAreUniqueAndFindable) {
  std::set<std::string> names;
  for (const ElementKind* k : elementKinds()) {
    EXPECT_TRUE(names.insert(k->name()).second) << k->name();
    EXPECT_EQ(findElementKind(k->name()), k);
  }
  EXPECT_EQ(names, (std::set<std::string>{"membrane", "cable", "point_mass", "bar"}));
  EXPECT_EQ(findElementKind("membrain"), nullptr);
}

TEST(ElementKinds, EveryMaterialTypeFeedsARegisteredKind) {
  std::set<std::string> types;
  for (const MaterialType& t : materialTypes()) {
    EXPECT_TRUE(types.insert(t.name).second) << t.name;
    EXPECT_NE(findElementKind(t.elementKind), nullptr) << t.name << " feeds '" << t.elementKind << "'";
    EXPECT_NE(t.read, nullptr);
  }
}

TEST(ElementKinds, OutputFieldsAreValidSceneFields) {
  const auto& all = allOutputFields();
  for (const ElementKind* k : elementKinds())
    for (const std::string& f : k->outputFields())
      EXPECT_NE(std::find(all.begin(), all.end(), f), all.end()) << k->name() << ": " << f;
}

// A mixed model: each kind counts its own elements, and the lumped masses they add sum to ρ t A of the sheet
// plus ρ A L of the cable (the model's total mass, computed here from the inputs).
TEST(ElementKinds, CountAndLumpedMassOfAMixedModel) {
  RectangleParams rp;
  rp.size = {2.0, 1.0};
  rp.divisions = {4, 2};
  MeshInput sheet;
  sheet.mesh = rectangle(rp, "sheet");
  sheet.membraneMaterial = 0;
  CableChainParams cp;
  cp.points = {{0, 0, 1}, {0, 0, 4}};
  cp.divisions = {3};
  MeshInput line;
  line.mesh = cableChain(cp, "line");
  line.cableMaterial = 0;
  Model m = buildModel({sheet, line}, {MembraneMaterial{"f", 1e9, 0.3, 2e-3, 500, true}},
                       {CableMaterial{"c", 1e9, 1e-4, 1500}});
  EXPECT_EQ(findElementKind("membrane")->count(m), 16);
  EXPECT_EQ(findElementKind("cable")->count(m), 3);
  double total = 0;
  for (double v : m.nodes.mass) total += v;
  EXPECT_NEAR(total, 500 * 2e-3 * 2.0 + 1500 * 1e-4 * 3.0, 1e-12 * total);
  std::vector<double> cableOnly(m.nodes.count, 0.0);
  findElementKind("cable")->addLumpedMass(m, cableOnly);
  double c = 0;
  for (double v : cableOnly) c += v;
  EXPECT_NEAR(c, 1500 * 1e-4 * 3.0, 1e-12 * c);
  EXPECT_EQ(findElementKind("cable")->describe(m, 0).rfind("cable ", 0), 0u);
  EXPECT_EQ(findElementKind("membrane")->describe(m, 0).rfind("triangle ", 0), 0u);
}

namespace {

// Three 1 m cables hanging from the origin (material 0).
MeshInput verticalLine() {
  CableChainParams cp;
  cp.points = {{0, 0, 0}, {0, 0, -3}};
  cp.divisions = {3};
  MeshInput line;
  line.mesh = cableChain(cp, "line");
  line.cableMaterial = 0;
  return line;
}

}  // namespace

// A mesh's per-line rest lengths (MeshData::lineRestLength, e.g. the parafoil's brake slack) replace the
// distance of the cable's ends where non-zero; a rest length that is not positive and finite is refused with
// the cable named.
TEST(ElementKinds, LineRestLengthsReplaceTheGeometricLengthAndBadOnesNameTheCable) {
  MeshInput line = verticalLine();
  const std::vector<CableMaterial> cable{CableMaterial{"c", 1e9, 1e-4, 1500}};
  line.mesh.lineRestLength = {0.0, 1.25, 0.0};  // 0: the geometric length (1 m)
  Model m = buildModel({line}, {}, cable);
  ASSERT_EQ(m.cables.count, 3);
  std::vector<double> rest(m.cables.restLength);
  std::sort(rest.begin(), rest.end());
  EXPECT_DOUBLE_EQ(rest[0], 1.0);
  EXPECT_DOUBLE_EQ(rest[1], 1.0);
  EXPECT_DOUBLE_EQ(rest[2], 1.25);
  for (double bad :
       {-0.5, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    line.mesh.lineRestLength = {0.0, bad, 0.0};
    try {
      buildModel({line}, {}, cable);
      ADD_FAILURE() << "rest length " << bad << " accepted";
    } catch (const fsi::InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("cable"), std::string::npos) << what;
      EXPECT_NE(what.find("rest length"), std::string::npos) << what;
      EXPECT_NE(what.find("must be positive and finite"), std::string::npos) << what;
    }
  }
}

namespace {

std::string materialError(const std::string& film) {
  const std::string yaml = "materials:\n  film: " + film + R"(
meshes:
  sheet:
    generator: {type: rectangle, size: [1, 1], divisions: [2, 2]}
    material: film
time: {end: 1.0e-3}
)";
  try {
    loadSceneFromString(yaml, "m.yaml");
  } catch (const std::exception& e) {
    return e.what();
  }
  return {};
}

}  // namespace

// The scene's materials block reads through the registry: its types and each type's keys are the valid ones,
// with "did you mean" and located messages.
// Each kind's scene reader (structure/scene/kinds) declares the keys of a scene's mesh entry it reads; the
// mesh reader accepts exactly those (plus where the mesh comes from), so a misspelt key is answered from the
// registry. Every reader reads for a registered kind, and every kind has a reader.
TEST(ElementKinds, DeclareTheMeshKeysTheyRead) {
  std::map<std::string, std::vector<std::string>> byKind;
  for (const KindReader& r : kindReaders()) {
    EXPECT_NE(findElementKind(r.kind), nullptr) << r.kind;
    byKind[r.kind] = r.schema->names();
  }
  EXPECT_EQ(byKind.size(), elementKinds().size());
  EXPECT_EQ(byKind["membrane"], std::vector<std::string>{"material"});
  EXPECT_EQ(byKind["cable"], (std::vector<std::string>{"cable_material", "cables", "edge_cables"}));
  EXPECT_EQ(byKind["point_mass"], std::vector<std::string>{"point_masses"});
  EXPECT_EQ(byKind["bar"], (std::vector<std::string>{"bar_material", "bars"}));
  std::set<std::string> keys;
  for (const KindReader& r : kindReaders())
    for (const std::string& key : r.schema->names()) EXPECT_TRUE(keys.insert(key).second) << key;
  const char* yaml = R"(materials:
  line: {type: cable, young: 1.0e9, area: 1.0e-4, density: 1000}
  payload: {type: point_mass, mass: 5}
meshes:
  riser:
    generator: {type: cable_chain, points: [[0, 0, 0], [0, 0, -1]], divisions: [2]}
    cable_material: line
    point_mass: {end: payload}
)";
  std::string what;
  try {
    loadSceneFromString(yaml, "keys.yaml");
  } catch (const fsi::InputError& e) {
    what = e.what();
  }
  EXPECT_NE(what.find("keys.yaml:8"), std::string::npos) << what;
  EXPECT_NE(what.find("did you mean 'point_masses'"), std::string::npos) << what;
}

// Which Physical Curves of a Gmsh file are cables is said (`cables: [NAMES]` or `cables: all`), not assumed:
// a curve named for a constraint stays a node set. A file with curves and a cable_material but no `cables` is
// an error naming the key and the curves; without a cable_material every curve is a node set; an unknown name
// is an error listing the curves there are.
TEST(ElementKinds, CablesOfAMeshFileAreNamedTheOtherCurvesStayNodeSets) {
  const std::filesystem::path dir = fsi::test::outDir("curves");
  std::filesystem::create_directories(dir);
  {
    // a unit square of two triangles; curve `edge` along y = 0 (for a constraint), curve `diagonal` a cable
    std::ofstream out(dir / "sheet.msh");
    out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n3\n1 1 \"edge\"\n1 2 \"diagonal\"\n"
           "2 3 \"sheet\"\n$EndPhysicalNames\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n$EndNodes\n"
           "$Elements\n4\n1 1 2 1 1 1 2\n2 1 2 2 2 1 3\n3 2 2 3 3 1 2 3\n4 2 2 3 3 1 3 4\n$EndElements\n";
  }
  auto scene = [&](const std::string& keys) {
    std::ofstream out(dir / "s.yaml");
    out << "materials:\n  film: {type: membrane, young: 1.0e8, poisson: 0.3, thickness: 1.0e-3, density: "
           "1000}\n"
           "  rope: {type: cable, young: 1.0e10, area: 1.0e-6, density: 1000}\n"
           "meshes:\n  sheet: {file: sheet.msh, material: film"
        << keys << "}\nconstraints:\n  - {nodes: sheet/edge, fix: all}\ntime: {end: 1.0e-4}\n";
    out.close();
    return loadScene(dir / "s.yaml");
  };
  const Scene named = scene(", cable_material: rope, cables: [diagonal]");
  EXPECT_EQ(named.model->cables.count, 1);  // the diagonal; the edge is the constraint's node set
  EXPECT_EQ(named.constraints.fixedDofs.size(), 6u);
  EXPECT_EQ(scene(", cable_material: rope, cables: all").model->cables.count, 2);
  const Scene plain = scene("");
  EXPECT_EQ(plain.model->cables.count, 0);
  EXPECT_EQ(plain.constraints.fixedDofs.size(), 6u);
  std::string what;
  try {
    scene(", cable_material: rope");
  } catch (const fsi::InputError& e) {
    what = e.what();
  }
  EXPECT_NE(what.find("Physical Curves: diagonal, edge"), std::string::npos) << what;
  EXPECT_NE(what.find("'cables: [NAMES]'"), std::string::npos) << what;
  what.clear();
  try {
    scene(", cable_material: rope, cables: [rim]");
  } catch (const fsi::InputError& e) {
    what = e.what();
  }
  EXPECT_NE(what.find("no line group (Physical Curve) 'rim'; it has: diagonal, edge"), std::string::npos)
      << what;
}

// edge_cables: a cable along each boundary edge of a generated membrane inside a node group, without a mesh
// file: a 4 x 2 rectangle's side xmax (2 edges) and ymin (4 edges) get 6 cables sharing the membrane's nodes,
// under line groups of the sets' names; a set without a boundary edge, or an unknown one, is refused at the
// key.
TEST(ElementKinds, EdgeCablesFollowAGeneratedMembranesEdges) {
  auto yaml = [](const std::string& sets,
                 const std::string& generator =
                     "{type: rectangle, size: [2, 1], divisions: [4, 2], center: [1, 0.5, 0]}") {
    return "materials:\n  film: {type: membrane, young: 1.0e8, poisson: 0.3, thickness: 1.0e-3, density: "
           "1000}\n"
           "  rope: {type: cable, young: 1.0e10, area: 1.0e-6, density: 1000}\n"
           "meshes:\n  sheet:\n    generator: " +
           generator + "\n    material: film\n    cable_material: rope\n    edge_cables: " + sets +
           "\nconstraints:\n  - {nodes: sheet/all, fix: all}\ntime: {end: 1.0e-4}\n";
  };
  const Scene scene = loadSceneFromString(yaml("[xmax, ymin]"), "edges.yaml");
  const Model& m = *scene.model;
  ASSERT_EQ(m.cables.count, 6);
  for (int e = 0; e < m.cables.count; ++e) {
    const int a = m.cables.conn[2 * e], b = m.cables.conn[2 * e + 1];
    const double dx = m.nodes.X[3 * a] - m.nodes.X[3 * b], dy = m.nodes.X[3 * a + 1] - m.nodes.X[3 * b + 1];
    EXPECT_NEAR(std::hypot(dx, dy), 0.5, 1e-12) << "cable " << e << " is not one edge of the 0.5 m cells";
    const bool onXmax = m.nodes.X[3 * a] == 2.0 && m.nodes.X[3 * b] == 2.0;
    const bool onYmin = m.nodes.X[3 * a + 1] == 0.0 && m.nodes.X[3 * b + 1] == 0.0;
    EXPECT_TRUE(onXmax || onYmin) << "cable " << e;
  }
  EXPECT_EQ(m.nodes.count, 15);  // the membrane's own nodes: the cables add none
  const std::string disc = "{type: disc, radius: 0.5, rings: 4}";
  EXPECT_EQ(loadSceneFromString(yaml("[rim]", disc), "disc.yaml").model->cables.count > 0, true);
  EXPECT_NE(sceneError(yaml("[center]", disc), "disc.yaml").find("no edge on the boundary"),
            std::string::npos);
  EXPECT_NE(sceneError(yaml("[rim]"), "edges.yaml").find("no node group 'rim'"), std::string::npos);
}

// A kind other than membranes and cables builds its own block of the model (buildModel calls it with the
// meshes and the whole material table) and finds it again by its name: the point mass, from what its mesh key
// left in the mesh input.
TEST(ElementKinds, AKindBuildsItsOwnBlockFromTheMeshes) {
  MeshInput line = verticalLine();
  line.kindInputs["point_mass"] = PointMassInput{{3, 0}};
  MaterialTable table;
  table.cable = {CableMaterial{"c", 1e9, 1e-4, 1500}};
  table.pointMass = {PointMassMaterial{"payload", 70}};
  Model m = buildModel({line}, table);
  const PointMasses* P = m.block<PointMasses>("point_mass");
  ASSERT_NE(P, nullptr);
  ASSERT_EQ(P->count, 1);
  EXPECT_EQ(P->node[0], m.meshes[0].node[3]);
  EXPECT_EQ(findElementKind("point_mass")->count(m), 1);
  // Half of the last cable (ρ A L_e / 2) plus the payload.
  EXPECT_NEAR(m.nodes.physicalMass[P->node[0]], 70 + 0.5 * 1500 * 1e-4 * 1.0, 1e-12);
  // A model without point-mass input has an empty block, and the kind counts none.
  line.kindInputs.clear();
  EXPECT_EQ(findElementKind("point_mass")->count(buildModel({line}, table)), 0);
  // The kind's own checks name the mesh.
  line.kindInputs["point_mass"] = PointMassInput{{9, 0}};
  try {
    buildModel({line}, table);
    ADD_FAILURE() << "no error";
  } catch (const fsi::InputError& e) {
    EXPECT_STREQ(e.what(), "mesh 'line': point mass 1 refers to node index 9 out of range");
  }
}

TEST(MaterialTypes, SceneMaterialsComeFromTheRegistry) {
  EXPECT_EQ(materialError("{type: membrane, young: 1.0e8, poisson: 0.3, thickness: 1.0e-3, density: 1000}"),
            "");
  const std::string type = materialError("{type: membrn, young: 1.0e8}");
  EXPECT_NE(type.find("m.yaml:2:"), std::string::npos) << type;
  EXPECT_NE(type.find("materials.film.type"), std::string::npos) << type;
  EXPECT_NE(type.find("did you mean 'membrane'"), std::string::npos) << type;
  EXPECT_NE(type.find("cable"), std::string::npos) << type;  // lists the registered types
  const std::string key = materialError(
      "{type: membrane, young: 1.0e8, poisson: 0.3, thickness: 1.0e-3, density: 1000, wrinklng: false}");
  EXPECT_NE(key.find("unknown key 'wrinklng'"), std::string::npos) << key;
  EXPECT_NE(key.find("did you mean 'wrinkling'"), std::string::npos) << key;
  const std::string cableKey =
      materialError("{type: cable, young: 1.0e9, area: 1.0e-4, density: 1000, wrinkling: false}");
  EXPECT_NE(cableKey.find("unknown key 'wrinkling'"), std::string::npos) << cableKey;  // a membrane key
  const std::string value = materialError("{type: cable, young: 1.0e9, area: -1, density: 1000}");
  EXPECT_NE(value.find("materials.film.area: must be > 0"), std::string::npos) << value;
}
