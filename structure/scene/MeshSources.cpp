#include "structure/scene/MeshSources.hpp"

#include <fmt/format.h>

#include "structure/io/GmshReader.hpp"
#include "structure/model/Error.hpp"
#include "structure/parafoil/ParafoilScene.hpp"
#include "structure/scene/Generators.hpp"

namespace fsi::structure {

namespace {

std::vector<Point3> points(const YamlMap& g, const std::string& key) {
  const YAML::Node n = g.raw(key);
  if (!n || !n.IsSequence() || n.size() < 2) g.failAt(key, "expected a list of at least 2 points [x, y, z]");
  std::vector<Point3> out;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const std::string p = fmt::format("{}[{}]", g.childPath(key), i);
    if (!n[i].IsSequence() || n[i].size() != 3)
      throw InputError(locate(g.file(), n[i], p) + ": expected [x, y, z]");
    out.push_back(
        {asNumber(n[i][0], g.file(), p), asNumber(n[i][1], g.file(), p), asNumber(n[i][2], g.file(), p)});
  }
  return out;
}

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

// Generator messages name the parameter; add where in the scene it came from. YAML errors are already
// located and pass through unchanged.
template <class Params, class Fn>
MeshData located(const YamlMap& g, Fn fn, const Params& p, const std::string& name) {
  try {
    return fn(p, name);
  } catch (const InputError& e) {
    throw InputError(locate(g.file(), g.node(), g.path()) + ": " + e.what());
  }
}

MeshData generate(const YamlMap& g, const std::string& name, const std::filesystem::path& sceneDir) {
  const std::string type =
      g.choice("type", {"rectangle", "disc", "sphere_octant", "cable_chain", "strip", "pillow", "parafoil"});
  {
    if (type == "parafoil") {
      const auto p = parafoil::readParafoilParams(g, sceneDir);
      return located(g, parafoil::buildParafoil, p, name);
    }
    if (type == "rectangle") {
      auto p = rectangleParams(g);
      g.finish({"type", "size", "divisions", "center", "pattern"});
      return located(g, rectangle, p, name);
    }
    if (type == "disc") {
      auto p = discParams(g);
      g.finish({"type", "radius", "rings", "center"});
      return located(g, disc, p, name);
    }
    if (type == "sphere_octant") {
      SphereOctantParams p;
      p.radius = g.number("radius");
      p.divisions = int(g.integer("divisions"));
      g.finish({"type", "radius", "divisions"});
      return located(g, sphereOctant, p, name);
    }
    if (type == "cable_chain") {
      CableChainParams p;
      p.points = points(g, "points");
      p.divisions = toInts(g.integers("divisions"));
      g.finish({"type", "points", "divisions"});
      return located(g, cableChain, p, name);
    }
    if (type == "strip") {
      StripParams p;
      p.path = points(g, "path");
      p.divisions = toInts(g.integers("divisions"));
      p.width = g.vec3("width");
      p.across = int(g.integer("across", 1));
      p.pattern = g.choice("pattern", {"ruled", "alternating"}, "ruled");
      g.finish({"type", "path", "divisions", "width", "across", "pattern"});
      return located(g, strip, p, name);
    }
    PillowParams p;
    p.shape = g.choice("shape", {"rectangle", "disc"});
    if (p.shape == "rectangle") {
      p.rectangle = rectangleParams(g);
      g.finish({"type", "shape", "size", "divisions", "center", "pattern"});
    } else {
      p.disc = discParams(g);
      g.finish({"type", "shape", "radius", "rings", "center"});
    }
    return located(g, pillow, p, name);
  }
}

}  // namespace

MeshData meshFromScene(const YamlMap& entry, const std::string& name, const std::filesystem::path& sceneDir) {
  const bool hasFile = entry.has("file"), hasGen = entry.has("generator");
  if (hasFile == hasGen) entry.fail("a mesh needs exactly one of 'file' (Gmsh .msh) or 'generator'");
  if (hasFile) {
    const std::filesystem::path f = sceneDir / entry.string("file");
    try {
      return readGmsh(f, name);
    } catch (const InputError& e) {
      throw InputError(locate(entry.file(), entry.raw("file"), entry.childPath("file")) + ": " + e.what());
    }
  }
  return generate(entry.map("generator"), name, sceneDir);
}

}  // namespace fsi::structure
