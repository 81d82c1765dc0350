#include "structure/scene/SelectorSchema.hpp"

namespace fsi::structure {

namespace {

SceneKey among() {
  return {"among",
          KeyType::Selector,
          "",
          "",
          "all nodes of all meshes",
          {},
          {},
          {},
          "a node selector the search is restricted to"};
}

}  // namespace

const SchemaSection& setsSchema() {
  static const SchemaSection s{
      "sets",
      "named selectors, resolved as node or triangle selectors where they are used (a set may refer to other "
      "sets, not in a cycle, and may not have a mesh's name)",
      {{"NAME",
        KeyType::Selector,
        "",
        "",
        "",
        {},
        {},
        {},
        "any selector: `name`, `mesh/group`, `[sel, ...]` (their union) or a node selector's mapping form"}}};
  return s;
}

const SchemaSection& planeSelectorSchema() {
  static const SchemaSection s{
      "selector {plane: ...}",
      "the nodes within `tolerance` of a plane (reference coordinates)",
      {{"plane",
        KeyType::Map,
        "m",
        "",
        "required",
        {},
        {},
        {},
        "`{point: [x, y, z], normal: [nx, ny, nz]}`, both required, normal non-zero"},
       {"tolerance",
        KeyType::Number,
        "m",
        "1e-9",
        "",
        {},
        {},
        {},
        "distance from the plane (beside `plane`, not inside it)"},
       among()}};
  return s;
}

const SchemaSection& boxSelectorSchema() {
  static const SchemaSection s{
      "selector {box: ...}",
      "the nodes inside an axis-aligned box, bounds included (reference coordinates)",
      {{"box",
        KeyType::Map,
        "m",
        "",
        "required",
        {},
        {},
        {},
        "`{min: [x, y, z], max: [x, y, z]}`, both required"},
       among()}};
  return s;
}

const SchemaSection& nearestSelectorSchema() {
  static const SchemaSection s{
      "selector {nearest: ...}",
      "the one node closest to a point (reference coordinates)",
      {{"nearest", KeyType::Vec3, "m", "", "required", {}, {}, {}, "the point"}, among()}};
  return s;
}

const SchemaSection& idsSelectorSchema() {
  static const SchemaSection s{
      "selector {ids: ...}",
      "nodes of one mesh by id (Gmsh node tag, or generator id 1..n); an unknown id is an error",
      {{"ids", KeyType::Any, "", "", "required", {}, {}, {}, "an id or a list of ids (integers)"},
       {"mesh", KeyType::String, "", "", "required", {}, {}, {}, "the mesh"}}};
  return s;
}

}  // namespace fsi::structure
