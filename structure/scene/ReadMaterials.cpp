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

MaterialTable readSceneMaterials(const YamlMap& top) {
  return readMaterials(top.map("materials"));
}

const std::map<std::string, int>& materialsOfKind(const MaterialTable& table, const std::string& kind) {
  static const std::map<std::string, int> none;
  const auto it = table.index.find(kind);
  return it == table.index.end() ? none : it->second;
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
