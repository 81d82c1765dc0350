#pragma once
// "a, b, c": how the scene reader lists valid names in its messages.
#include <string>
#include <vector>

namespace fsi::structure {

inline std::string joinNames(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

}  // namespace fsi::structure
