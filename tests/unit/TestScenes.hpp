#pragma once
// Scene text shared by several tests: a 1 m square film (8x8 cross-pattern squares) clamped on its edges.

#include <filesystem>
#include <string>

namespace fsi::test {

/// An empty output folder for one test under the build tree (per test, so parallel ctest runs do not share).
inline std::filesystem::path outDir(const std::string& name) {
  const std::filesystem::path d = std::filesystem::path(FSI_BINARY_DIR) / "test-output" / name;
  std::filesystem::remove_all(d);
  return d;
}

inline std::string drumScene(const std::string& extra) {
  return std::string(R"(materials:
  film: {type: membrane, young: 1.0e8, poisson: 0.3, thickness: 1.0e-3, density: 1000}
meshes:
  sheet:
    generator: {type: rectangle, size: [1, 1], divisions: [8, 8], pattern: cross}
    material: film
constraints:
  - {nodes: sheet/boundary, fix: all}
)") + extra;
}

}  // namespace fsi::test
