#pragma once
// Strict, located access to a YAML scene: every value is read through a YamlMap that knows its file, its
// key path and its line, so every error says where it is and what would have been valid. Keys that nobody
// read are errors (a typo never silently falls back to a default).

#include <yaml-cpp/yaml.h>

#include <array>
#include <set>
#include <string>
#include <vector>

namespace fsi::structure {

/// "file:line:col: path: message" for a node (line/col omitted for values set on the command line).
std::string locate(const std::string& file, const YAML::Node& node, const std::string& path);

/// Closest candidate by edit distance, or "" if none is close.
std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates);

class YamlMap {
 public:
  YamlMap(YAML::Node node, std::string file, std::string path);

  bool has(const std::string& key) const;
  double number(const std::string& key) const;
  double number(const std::string& key, double fallback) const;
  long integer(const std::string& key) const;
  long integer(const std::string& key, long fallback) const;
  bool boolean(const std::string& key, bool fallback) const;
  std::string string(const std::string& key) const;
  std::string string(const std::string& key, const std::string& fallback) const;
  /// A string that must be one of `choices`.
  std::string choice(const std::string& key, const std::vector<std::string>& choices) const;
  std::string choice(const std::string& key, const std::vector<std::string>& choices,
                     const std::string& fallback) const;
  std::array<double, 3> vec3(const std::string& key) const;
  std::array<double, 3> vec3(const std::string& key, std::array<double, 3> fallback) const;
  std::vector<double> numbers(const std::string& key) const;
  std::vector<long> integers(const std::string& key) const;
  std::vector<std::string> strings(const std::string& key) const;
  YamlMap map(const std::string& key) const;
  YAML::Node raw(const std::string& key) const;  ///< marks the key as used
  std::string childPath(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

  /// Throws unless every key of the mapping was read; the message lists valid keys and a suggestion.
  void finish(const std::vector<std::string>& validKeys) const;
  /// Throws with this map's location.
  [[noreturn]] void fail(const std::string& message) const;
  [[noreturn]] void failAt(const std::string& key, const std::string& message) const;

  const YAML::Node& node() const { return node_; }
  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  std::vector<std::string> keys() const;

 private:
  YAML::Node require(const std::string& key) const;
  YAML::Node node_;
  std::string file_, path_;
  mutable std::set<std::string> used_;
};

/// Reads a number from a scalar node with a located error.
double asNumber(const YAML::Node& n, const std::string& file, const std::string& path);

/// Applies "a.b.0.c=value" overrides (value parsed as YAML) to a loaded document.
void applyOverride(YAML::Node& root, const std::string& assignment);

}  // namespace fsi::structure
