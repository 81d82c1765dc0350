#pragma once
// Helpers of the kinds' scene readers that work on a mesh's line groups (structure/scene/kinds).

#include <map>
#include <string>
#include <vector>

namespace fsi::structure {

/// "a, b, c" of a group map's names, or "none".
std::string groupList(const std::map<std::string, std::vector<int>>& groups);

}  // namespace fsi::structure
