#include "structure/scene/ReadMaterials.hpp"

#include <fmt/format.h>

#include <cmath>

#include "structure/scene/JoinNames.hpp"

namespace fsi::structure {

namespace {
std::string join(const std::vector<std::string>& v) {
  return joinNames(v);
}
}  // namespace

// The block below is moved verbatim from Scene.cpp's loader (helper E rewrites it through a material
// registry).
MaterialTable readMaterials(const YamlMap& top) {
  std::map<std::string, int> membraneIdx, cableIdx;
  std::vector<MembraneMaterial> membraneMats;
  std::vector<CableMaterial> cableMats;
  {
    YamlMap mats = top.map("materials");
    for (const auto& name : mats.keys()) {
      YamlMap m = mats.map(name);
      const std::string type = m.choice("type", {"membrane", "cable"});
      if (type == "membrane") {
        MembraneMaterial mm;
        mm.name = name;
        mm.young = m.number("young");
        mm.poisson = m.number("poisson");
        mm.thickness = m.number("thickness");
        mm.density = m.number("density");
        mm.wrinkling = m.boolean("wrinkling", true);
        m.finish({"type", "young", "poisson", "thickness", "density", "wrinkling"});
        if (!(mm.young > 0)) m.failAt("young", "must be > 0");
        if (!(mm.poisson >= 0 && mm.poisson < 0.5)) m.failAt("poisson", "must be in [0, 0.5)");
        if (!(mm.thickness > 0)) m.failAt("thickness", "must be > 0");
        if (!(mm.density > 0) || !std::isnormal(mm.density))
          m.failAt("density",
                   "must be > 0 and at least 2.2e-308 (a smaller, subnormal density makes the lumped masses "
                   "underflow to 0)");
        membraneIdx[name] = int(membraneMats.size());
        membraneMats.push_back(mm);
      } else {
        CableMaterial cm;
        cm.name = name;
        cm.young = m.number("young");
        cm.area = m.number("area");
        cm.density = m.number("density");
        m.finish({"type", "young", "area", "density"});
        if (!(cm.young > 0)) m.failAt("young", "must be > 0");
        if (!(cm.area > 0)) m.failAt("area", "must be > 0");
        if (!(cm.density > 0) || !std::isnormal(cm.density))
          m.failAt("density",
                   "must be > 0 and at least 2.2e-308 (a smaller, subnormal density makes the lumped masses "
                   "underflow to 0)");
        cableIdx[name] = int(cableMats.size());
        cableMats.push_back(cm);
      }
    }
  }
  return {std::move(membraneIdx), std::move(cableIdx), std::move(membraneMats), std::move(cableMats)};
}

int materialRef(const YamlMap& m, const std::string& key, const std::map<std::string, int>& idx,
                const std::string& kind) {
  const std::string n = m.string(key);
  const auto it = idx.find(n);
  if (it == idx.end()) {
    std::vector<std::string> names;
    for (const auto& kv : idx) names.push_back(kv.first);
    const std::string near = closestMatch(n, names);
    m.failAt(key, fmt::format("no {} material named '{}'{}; {} materials: {}", kind, n,
                              near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near), kind,
                              names.empty() ? "(none defined)" : join(names)));
  }
  return it->second;
}

}  // namespace fsi::structure
