#pragma once
// Scene text shared by several tests: a 1 m square film (8x8 cross-pattern squares) clamped on its edges.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "structure/model/Error.hpp"
#include "structure/scene/Scene.hpp"

namespace fsi::test {

/// An empty output folder for one test under the build tree (per test, so parallel ctest runs do not share).
/// ctest runs every test in a process of its own, in parallel, so a folder shared by two tests (a helper's
/// fixed name) would be emptied by one while the other writes into it: the folder sits under the test's name.
inline std::filesystem::path outDir(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string test =
      info != nullptr ? std::string(info->test_suite_name()) + "." + info->name() : std::string("no-test");
  const std::filesystem::path d = std::filesystem::path(FSI_BINARY_DIR) / "test-output" / test / name;
  std::filesystem::remove_all(d);
  return d;
}

/// The message of the InputError loading `yaml` (named `name` in messages) throws; empty if it loads.
inline std::string sceneError(const std::string& yaml, const std::string& name) {
  try {
    fsi::structure::loadSceneFromString(yaml, name);
  } catch (const fsi::InputError& e) {
    return e.what();
  }
  return "";
}

/// `s` with its first `from` replaced by `to` (a test failure if `from` is not there).
inline std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  return p == std::string::npos ? s : s.replace(p, from.size(), to);
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
