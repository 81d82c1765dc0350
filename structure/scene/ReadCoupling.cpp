#include "structure/scene/ReadCoupling.hpp"

#include <algorithm>

#include "structure/scene/SceneSchema.hpp"

namespace fsi::structure {

// The `coupling:` section: the triangles that receive the flow's load and the rule for the load within a
// window. The scene builds no effect for it: the coupling participant owns the load and adds the
// InterfacePressure effect that reads it.
const SchemaSection& couplingSchema() {
  static const SchemaSection s{
      "coupling",
      "the interface a flow solver loads (docs/COUPLING.md)",
      {{"interface",
        KeyType::Selector,
        "",
        "",
        "required",
        {},
        {},
        {},
        "the triangles the flow's load acts on"},
       {"load_in_window",
        KeyType::Choice,
        "",
        "mean",
        "",
        {},
        {},
        {"mean", "end", "linear"},
        "the load within a coupling window: the window's mean, its end value, or linear in time"}}};
  return s;
}

void readCoupling(const YamlMap& top, const SetResolver& sets, Scene& scene) {
  const Model& model = *scene.model;
  if (!top.has("coupling")) return;
  YamlMap cMap = top.map("coupling");
  const SchemaMap c(cMap, couplingSchema());
  const auto tris = sets.triangles(cMap.required("interface"), cMap.childPath("interface"));
  const std::string rule = c.string("load_in_window");
  c.finish();
  Scene::CouplingInterface ci;
  ci.loadInWindow = rule == "mean"  ? LoadInterpolation::ConstantMean
                    : rule == "end" ? LoadInterpolation::ConstantEnd
                                    : LoadInterpolation::Linear;
  for (int e : tris)
    for (int k = 0; k < 3; ++k) ci.triangles.push_back(model.membranes.conn[3 * e + k]);
  ci.nodes = ci.triangles;
  std::sort(ci.nodes.begin(), ci.nodes.end());
  ci.nodes.erase(std::unique(ci.nodes.begin(), ci.nodes.end()), ci.nodes.end());
  scene.couplingInterface = std::move(ci);
}

}  // namespace fsi::structure
