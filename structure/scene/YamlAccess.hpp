#pragma once
// Strict, located access to a YAML scene: every value is read through a YamlMap that knows its file, its
// key path and its line, so every error says where it is and what would have been valid. Keys that nobody
// read are errors (a typo never silently falls back to a default).

#include <yaml-cpp/yaml.h>

#include <array>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "structure/model/PositiveValue.hpp"
#include "structure/scene/NearestName.hpp"

namespace fsi::structure {

/// "file:line:col: path: message" for a node (line/col omitted for values set on the command line).
std::string locate(const std::string& file, const YAML::Node& node, const std::string& path);

/// Inclusive range an integer key must lie in. The default is the range of `int`, the type most integer
/// keys end up in, so that a value never wraps when it is narrowed.
struct IntRange {
  long lo = std::numeric_limits<int>::min();
  long hi = std::numeric_limits<int>::max();
};

/// Refuses text that is not UTF-8 anywhere (comments too), at file:line:col of the first bad byte.
void requireUtf8Text(const std::string& text, const std::string& file);

/// Parses exactly one YAML document from `text`; a syntax error or a second document is an InputError
/// located in `file`. The tree is not checked yet (see checkDocument), so that --set overrides can be
/// applied first and are checked with the rest.
YAML::Node parseDocument(const std::string& text, const std::string& file);

/// Checks a whole parsed document, because yaml-cpp accepts what the scene reader must not: every mapping
/// key is a plain scalar and appears once in its mapping (yaml-cpp keeps duplicates and lookups find the
/// first), all text is valid UTF-8, and aliases neither form a cycle nor expand the tree beyond a sane size
/// or depth. Throws an InputError naming file, line, column and key path.
void checkDocument(const YAML::Node& root, const std::string& file);

class YamlMap {
 public:
  YamlMap(YAML::Node node, std::string file, std::string path);

  bool has(const std::string& key) const;
  double number(const std::string& key) const;
  double number(const std::string& key, double fallback) const;
  /// A number > 0 under the rule of isPositiveNormal (a physical quantity).
  double positive(const std::string& key) const;
  double positive(const std::string& key, double fallback) const;
  /// An integer (written as one, or as an integral number such as 1e3) inside `range`.
  long integer(const std::string& key, IntRange range = {}) const;
  long integer(const std::string& key, long fallback, IntRange range) const;
  long integer(const std::string& key, long fallback) const { return integer(key, fallback, IntRange{}); }
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
  std::vector<long> integers(const std::string& key, IntRange range = {}) const;
  std::vector<std::string> strings(const std::string& key) const;
  YamlMap map(const std::string& key) const;
  YAML::Node raw(const std::string& key) const;  ///< marks the key as used; an invalid node when absent
  YAML::Node required(
      const std::string& key) const;  ///< marks the key as used; located error when absent or empty
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
  YAML::Node origin_;  ///< the node as read (an empty value keeps its place in the file for messages)
  std::string file_, path_;
  mutable std::set<std::string> used_;
};

/// True for a value that is absent, empty, `~`, `null` or tagged `!!null`: never a valid value.
bool isNullValue(const YAML::Node& n);

/// Reads a finite number from a scalar node with a located error. A quoted or `!!str` scalar is text, not a
/// number; null is no value (docs/SCENES.md, "Errors").
double asNumber(const YAML::Node& n, const std::string& file, const std::string& path);
/// A number under the rule of isPositiveNormal, with a located error.
double asPositive(const YAML::Node& n, const std::string& file, const std::string& path);

/// Reads an integer inside `range` from a scalar node with a located error.
long asInteger(const YAML::Node& n, const std::string& file, const std::string& path, IntRange range = {});

/// Applies "a.b.0.c=value" overrides (value parsed as YAML) to a loaded document.
void applyOverride(YAML::Node& root, const std::string& assignment);

}  // namespace fsi::structure
