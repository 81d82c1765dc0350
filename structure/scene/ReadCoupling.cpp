#include "structure/scene/ReadCoupling.hpp"

#include <algorithm>

namespace fsi::structure {

// The `coupling:` section: the triangles that receive the flow's load and the rule for the load within a
// window. The scene builds no effect for it: the coupling participant owns the load and adds the
// InterfacePressure effect that reads it.
void readCoupling(const YamlMap& top, const SetResolver& sets, Scene& scene) {
  const Model& model = *scene.model;
  if (!top.has("coupling")) return;
  YamlMap c = top.map("coupling");
  const auto tris = sets.triangles(c.required("interface"), c.childPath("interface"));
  const std::string rule = c.choice("load_in_window", {"mean", "end", "linear"}, "mean");
  c.finish({"interface", "load_in_window"});
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
