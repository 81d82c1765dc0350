#include "structure/scene/GeneratorKinds.hpp"

#include <fmt/format.h>

#include "structure/model/Error.hpp"
#include "structure/scene/Generators.hpp"

namespace fsi::structure {

namespace {

std::vector<int> toInts(const std::vector<long>& v) {
  return std::vector<int>(v.begin(), v.end());
}

RectangleParams rectangleParams(const YamlMap& g) {
  RectangleParams p;
  const auto size = g.numbers("size");
  const auto div = g.integers("divisions");
  if (size.size() != 2) g.failAt("size", "expected [Lx, Ly]");
  if (div.size() != 2) g.failAt("divisions", "expected [nx, ny]");
  p.size = {size[0], size[1]};
  p.divisions = {int(div[0]), int(div[1])};
  p.center = g.vec3("center", {0, 0, 0});
  p.pattern = g.choice("pattern", {"ruled", "alternating", "cross"}, "ruled");
  return p;
}

DiscParams discParams(const YamlMap& g) {
  DiscParams p;
  p.radius = g.number("radius");
  p.rings = int(g.integer("rings"));
  p.center = g.vec3("center", {0, 0, 0});
  return p;
}

// ---------------------------------------------------------------- one reader per generator

// The keys of each generator entry (the registry lists them; the readers check them).
const std::vector<std::string> kRectangleKeys{"type", "size", "divisions", "center", "pattern"};
const std::vector<std::string> kDiscKeys{"type", "radius", "rings", "center"};
const std::vector<std::string> kSphereOctantKeys{"type", "radius", "divisions"};
const std::vector<std::string> kCableChainKeys{"type", "points", "divisions"};
const std::vector<std::string> kStripKeys{"type", "path", "divisions", "width", "across", "pattern"};
const std::vector<std::string> kPillowRectangleKeys{"type",      "shape",  "size",
                                                    "divisions", "center", "pattern"};
const std::vector<std::string> kPillowDiscKeys{"type", "shape", "radius", "rings", "center"};
const std::vector<std::string> kPillowKeys{"type",   "shape",   "size",   "divisions",
                                           "center", "pattern", "radius", "rings"};

MeshData rectangleFrom(const YamlMap& g, const std::string& name) {
  auto p = rectangleParams(g);
  g.finish(kRectangleKeys);
  return locatedGenerate(g, rectangle, p, name);
}

MeshData discFrom(const YamlMap& g, const std::string& name) {
  auto p = discParams(g);
  g.finish(kDiscKeys);
  return locatedGenerate(g, disc, p, name);
}

MeshData sphereOctantFrom(const YamlMap& g, const std::string& name) {
  SphereOctantParams p;
  p.radius = g.number("radius");
  p.divisions = int(g.integer("divisions"));
  g.finish(kSphereOctantKeys);
  return locatedGenerate(g, sphereOctant, p, name);
}

MeshData cableChainFrom(const YamlMap& g, const std::string& name) {
  CableChainParams p;
  p.points = readPoints(g, "points");
  p.divisions = toInts(g.integers("divisions"));
  g.finish(kCableChainKeys);
  return locatedGenerate(g, cableChain, p, name);
}

MeshData stripFrom(const YamlMap& g, const std::string& name) {
  StripParams p;
  p.path = readPoints(g, "path");
  p.divisions = toInts(g.integers("divisions"));
  p.width = g.vec3("width");
  p.across = int(g.integer("across", 1));
  p.pattern = g.choice("pattern", {"ruled", "alternating"}, "ruled");
  g.finish(kStripKeys);
  return locatedGenerate(g, strip, p, name);
}

// The keys of a pillow depend on its shape: those of the rectangle or of the disc generator.
MeshData pillowFrom(const YamlMap& g, const std::string& name) {
  PillowParams p;
  p.shape = g.choice("shape", {"rectangle", "disc"});
  if (p.shape == "rectangle") {
    p.rectangle = rectangleParams(g);
    g.finish(kPillowRectangleKeys);
  } else {
    p.disc = discParams(g);
    g.finish(kPillowDiscKeys);
  }
  return locatedGenerate(g, pillow, p, name);
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

GeneratorKind parafoilGenerator();  // structure/parafoil/ParafoilScene.cpp

const std::vector<GeneratorKind>& generatorKinds() {
  // Register a new generator here: a row, or for a generator in a file of its own `myShapeGenerator(),` (with
  // `GeneratorKind myShapeGenerator();` declared above this function).
  static const std::vector<GeneratorKind> kinds{
      {"rectangle", kRectangleKeys, "flat rectangle, normal +z", rectangleFrom},
      {"disc", kDiscKeys, "flat disc of hexagonal rings, normal +z", discFrom},
      {"sphere_octant", kSphereOctantKeys, "one eighth of a sphere, normal outward", sphereOctantFrom},
      {"cable_chain", kCableChainKeys, "cable lines along a polyline", cableChainFrom},
      {"strip", kStripKeys, "strip swept from a polyline", stripFrom},
      {"pillow", kPillowKeys, "two faces (rectangle or disc) joined at their rim", pillowFrom},
      parafoilGenerator(),
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
