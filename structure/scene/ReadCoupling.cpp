#include "structure/scene/ReadCoupling.hpp"

#include <algorithm>

namespace fsi::structure {

void readCoupling(const YamlMap& top, const SetResolver& sets, Scene& scene) {
  const Model& model = *scene.model;
  if (top.has("coupling")) {
    YamlMap c = top.map("coupling");
    const auto tris = sets.triangles(c.required("interface"), c.childPath("interface"));
    const std::string rule = c.choice("load_in_window", {"mean", "end", "linear"}, "mean");
    scene.interfaceLoadRule = rule == "mean"  ? WindowLoad::Mean
                              : rule == "end" ? WindowLoad::End
                                              : WindowLoad::Linear;
    c.finish({"interface", "load_in_window"});
    std::vector<int> conn, nodes;
    for (int e : tris)
      for (int k = 0; k < 3; ++k) conn.push_back(model.membranes.conn[3 * e + k]);
    nodes = conn;
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    auto ip = std::make_unique<InterfacePressure>(std::move(conn), std::move(nodes));
    scene.interfacePressure = ip.get();
    scene.effects.push_back(std::move(ip));
    scene.enabledEffects.push_back("interface_pressure");
  }
}

}  // namespace fsi::structure
