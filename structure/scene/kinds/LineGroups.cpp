#include "structure/scene/kinds/LineGroups.hpp"

namespace fsi::structure {

std::string groupList(const std::map<std::string, std::vector<int>>& groups) {
  std::string names;
  for (const auto& [name, members] : groups) names += (names.empty() ? "" : ", ") + name;
  return names.empty() ? "none" : names;
}

}  // namespace fsi::structure
