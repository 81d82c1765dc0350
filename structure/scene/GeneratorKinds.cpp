#include "structure/scene/GeneratorKinds.hpp"

#include <fmt/format.h>

#include "structure/model/Error.hpp"
#include "structure/scene/Generators.hpp"

namespace fsi::structure {

namespace {

std::vector<int> toInts(const std::vector<long>& v) {
  return std::vector<int>(v.begin(), v.end());
}

// ---------------------------------------------------------------- the entries' schema sections

using T = KeyType;
constexpr KeyBound kAboveZero{0, false};
constexpr KeyBound kAtLeastOne{1, true};

SceneKey typeKey(const char* name) {
  return {"type", T::Choice, "", "", "required", {}, {}, {name}, "the generator"};
}

// The keys a rectangle and a disc share with the pillow of that shape.
std::vector<SceneKey> rectangleKeys() {
  return {{"size", T::Numbers, "m", "", "required", kAboveZero, {}, {}, "[Lx, Ly]"},
          {"divisions", T::Any, "", "", "required", {}, {}, {}, "[nx, ny], integers >= 1"},
          {"center", T::Vec3, "m", "[0, 0, 0]", "", {}, {}, {}, "the centre"},
          {"pattern",
           T::Choice,
           "",
           "ruled",
           "",
           {},
           {},
           {"ruled", "alternating", "cross"},
           "how squares are cut into triangles (cross: 4 per square about a centre node)"}};
}

std::vector<SceneKey> discKeys() {
  return {{"radius", T::Number, "m", "", "required", kAboveZero, {}, {}, "the radius"},
          {"rings", T::Integer, "", "", "required", kAtLeastOne, {}, {}, "rings of nodes (ring k has 6k)"},
          {"center", T::Vec3, "m", "[0, 0, 0]", "", {}, {}, {}, "the centre"}};
}

SchemaSection section(const char* name, const char* description, std::vector<SceneKey> keys) {
  keys.insert(keys.begin(), typeKey(name));
  return {std::string("meshes.NAME.generator (") + name + ")", description, std::move(keys)};
}

const SchemaSection& rectangleSchema() {
  static const SchemaSection s = section("rectangle", "flat rectangle, normal +z", rectangleKeys());
  return s;
}

const SchemaSection& discSchema() {
  static const SchemaSection s = section("disc", "flat disc of hexagonal rings, normal +z", discKeys());
  return s;
}

const SchemaSection& sphereOctantSchema() {
  static const SchemaSection s =
      section("sphere_octant", "one eighth of a sphere about the origin, normal outward",
              {{"radius", T::Number, "m", "", "required", kAboveZero, {}, {}, "the radius"},
               {"divisions", T::Integer, "", "", "required", kAtLeastOne, {}, {}, "divisions per edge"}});
  return s;
}

const SchemaSection& cableChainSchema() {
  static const SchemaSection s =
      section("cable_chain", "cable lines along a polyline",
              {{"points", T::Any, "m", "", "required", {}, {}, {}, "[[x, y, z], ...], at least 2"},
               {"divisions",
                T::Any,
                "",
                "",
                "required",
                {},
                {},
                {},
                "cables per segment: one integer >= 1 for all, or one per segment"}});
  return s;
}

const SchemaSection& stripSchema() {
  static const SchemaSection s =
      section("strip", "strip swept from a polyline by a width vector",
              {{"path", T::Any, "m", "", "required", {}, {}, {}, "[[x, y, z], ...], at least 2"},
               {"divisions",
                T::Any,
                "",
                "",
                "required",
                {},
                {},
                {},
                "elements per segment: one integer >= 1 for all, or one per segment"},
               {"width", T::Vec3, "m", "", "required", {}, {}, {}, "the sweep (not parallel to any segment)"},
               {"across", T::Integer, "", "1", "", kAtLeastOne, {}, {}, "elements across the width"},
               {"pattern",
                T::Choice,
                "",
                "ruled",
                "",
                {},
                {},
                {"ruled", "alternating"},
                "how quadrilaterals are cut into triangles"}});
  return s;
}

// The keys of a pillow depend on its shape: those of the rectangle or of the disc generator.
const SchemaSection& pillowSchema() {
  static const SchemaSection s = [] {
    std::vector<SceneKey> keys{{"shape",
                                T::Choice,
                                "",
                                "",
                                "required",
                                {},
                                {},
                                {"rectangle", "disc"},
                                "the faces' shape; then that generator's keys"}};
    for (const SceneKey& k : rectangleKeys()) keys.push_back(k);
    for (const SceneKey& k : discKeys())
      if (k.name != "center") keys.push_back(k);
    return section("pillow", "two faces (rectangle or disc) joined at their rim", keys);
  }();
  return s;
}

const SchemaSection& pillowRectangleSchema() {
  static const SchemaSection s = [] {
    std::vector<SceneKey> keys{pillowSchema().key("shape")};
    for (const SceneKey& k : rectangleKeys()) keys.push_back(k);
    return section("pillow", "", keys);
  }();
  return s;
}

const SchemaSection& pillowDiscSchema() {
  static const SchemaSection s = [] {
    std::vector<SceneKey> keys{pillowSchema().key("shape")};
    for (const SceneKey& k : discKeys()) keys.push_back(k);
    return section("pillow", "", keys);
  }();
  return s;
}

// ---------------------------------------------------------------- one reader per generator

RectangleParams rectangleParams(const SchemaMap& g) {
  RectangleParams p;
  const auto size = g.numbers("size");
  const auto div = g.map().integers("divisions");
  if (size.size() != 2) g.map().failAt("size", "expected [Lx, Ly]");
  if (div.size() != 2) g.map().failAt("divisions", "expected [nx, ny]");
  p.size = {size[0], size[1]};
  p.divisions = {int(div[0]), int(div[1])};
  p.center = g.vec3("center");
  p.pattern = g.string("pattern");
  return p;
}

DiscParams discParams(const SchemaMap& g) {
  DiscParams p;
  p.radius = g.number("radius");
  p.rings = int(g.integer("rings"));
  p.center = g.vec3("center");
  return p;
}

MeshData rectangleFrom(const YamlMap& entry, const std::string& name) {
  const SchemaMap g(entry, rectangleSchema());
  auto p = rectangleParams(g);
  g.finish();
  return locatedGenerate(entry, rectangle, p, name);
}

MeshData discFrom(const YamlMap& entry, const std::string& name) {
  const SchemaMap g(entry, discSchema());
  auto p = discParams(g);
  g.finish();
  return locatedGenerate(entry, disc, p, name);
}

MeshData sphereOctantFrom(const YamlMap& entry, const std::string& name) {
  const SchemaMap g(entry, sphereOctantSchema());
  SphereOctantParams p;
  p.radius = g.number("radius");
  p.divisions = int(g.integer("divisions"));
  g.finish();
  return locatedGenerate(entry, sphereOctant, p, name);
}

MeshData cableChainFrom(const YamlMap& entry, const std::string& name) {
  const SchemaMap g(entry, cableChainSchema());
  CableChainParams p;
  p.points = readPoints(entry, "points");
  p.divisions = toInts(entry.integers("divisions"));
  g.finish();
  return locatedGenerate(entry, cableChain, p, name);
}

MeshData stripFrom(const YamlMap& entry, const std::string& name) {
  const SchemaMap g(entry, stripSchema());
  StripParams p;
  p.path = readPoints(entry, "path");
  p.divisions = toInts(entry.integers("divisions"));
  p.width = g.vec3("width");
  p.across = int(g.integer("across"));
  p.pattern = g.string("pattern");
  g.finish();
  return locatedGenerate(entry, strip, p, name);
}

MeshData pillowFrom(const YamlMap& entry, const std::string& name) {
  PillowParams p;
  p.shape = SchemaMap(entry, pillowSchema()).string("shape");
  if (p.shape == "rectangle") {
    const SchemaMap g(entry, pillowRectangleSchema());
    p.rectangle = rectangleParams(g);
    g.finish();
  } else {
    const SchemaMap g(entry, pillowDiscSchema());
    p.disc = discParams(g);
    g.finish();
  }
  return locatedGenerate(entry, pillow, p, name);
}

}  // namespace

std::vector<std::array<double, 3>> readPoints(const YamlMap& g, const std::string& key) {
  const YAML::Node n = g.raw(key);
  if (!n || !n.IsSequence() || n.size() < 2) g.failAt(key, "expected a list of at least 2 points [x, y, z]");
  std::vector<std::array<double, 3>> out;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const std::string p = fmt::format("{}[{}]", g.childPath(key), i);
    if (!n[i].IsSequence() || n[i].size() != 3)
      throw InputError(locate(g.file(), n[i], p) + ": expected [x, y, z]");
    out.push_back(
        {asNumber(n[i][0], g.file(), p), asNumber(n[i][1], g.file(), p), asNumber(n[i][2], g.file(), p)});
  }
  return out;
}

GeneratorKind parafoilGenerator();     // structure/parafoil/ParafoilScene.cpp
GeneratorKind roundCanopyGenerator();  // structure/roundcanopy/RoundCanopyScene.cpp

const std::vector<GeneratorKind>& generatorKinds() {
  // Register a new generator here: a row, or for a generator in a file of its own `myShapeGenerator(),` (with
  // `GeneratorKind myShapeGenerator();` declared above this function).
  static const std::vector<GeneratorKind> kinds{
      {"rectangle", rectangleSchema().names(), rectangleSchema().description, rectangleFrom,
       &rectangleSchema()},
      {"disc", discSchema().names(), discSchema().description, discFrom, &discSchema()},
      {"sphere_octant", sphereOctantSchema().names(), sphereOctantSchema().description, sphereOctantFrom,
       &sphereOctantSchema()},
      {"cable_chain", cableChainSchema().names(), cableChainSchema().description, cableChainFrom,
       &cableChainSchema()},
      {"strip", stripSchema().names(), stripSchema().description, stripFrom, &stripSchema()},
      {"pillow", pillowSchema().names(), pillowSchema().description, pillowFrom, &pillowSchema()},
      parafoilGenerator(),
      roundCanopyGenerator(),
  };
  return kinds;
}

MeshData generateMesh(const YamlMap& g, const std::string& meshName) {
  std::vector<std::string> types;
  for (const GeneratorKind& k : generatorKinds()) types.push_back(k.name);
  const std::string type = g.choice("type", types);
  for (const GeneratorKind& k : generatorKinds())
    if (k.name == type) return k.generate(g, meshName);
  g.failAt("type", "unknown generator");  // unreachable: choice() checked the name
}

}  // namespace fsi::structure
