#pragma once
// The declared keys of the scene schema as plain data (no YAML): a key's type, unit, default, range or
// choices and description, and a section of keys. The reader side (SchemaMap, the whole schema, its docs)
// is structure/scene/SceneSchema; the types are here so that a lower layer that owns a set of values (the
// materials: model/MaterialKeys) declares their ranges once and checks them with the same message.

#include <optional>
#include <string>
#include <vector>

namespace fsi::structure {

enum class KeyType {
  Number,    ///< a finite number
  Integer,   ///< an integer (written as one, or an integral number such as 1e3)
  Boolean,   ///< true or false
  String,    ///< text
  Choice,    ///< one word of `choices`
  Vec3,      ///< [x, y, z]
  Numbers,   ///< a number or a list of numbers
  Strings,   ///< a string or a list of strings
  Map,       ///< a mapping (its own section, or described in docs/SCENES.md)
  Selector,  ///< a node, triangle or line selector (docs/SCENES.md, "Selectors")
  Any,       ///< several forms (described); read by its section's own code
};
const char* toString(KeyType t);

/// One end of a numeric range.
struct KeyBound {
  double value = 0;
  bool inclusive = true;
};

/// Bounds as the tables write them: incl(0) is [0, …, excl(0) is (0, ….
inline KeyBound incl(double v) {
  return {v, true};
}
inline KeyBound excl(double v) {
  return {v, false};
}

/// An Integer key without an upper bound is read into an `int` (at most 2147483647, so that it never wraps);
/// this upper bound lets it take any `long` instead (shown as no upper bound).
inline constexpr KeyBound kAnyLong{9223372036854775807.0, true};

struct SceneKey {
  std::string name;
  KeyType type = KeyType::Any;
  std::string unit;          ///< SI unit ("m", "Pa", "deg", "-"); empty for words and counts
  std::string defaultValue;  ///< as a scene would write it ("3.0", "cosine", "true"); empty: none
  std::string defaultNote;   ///< a default that is not one value ("required", "unset: no taper", ...)
  std::optional<KeyBound> lower, upper;  ///< Number, Integer, Numbers, Vec3 (each component)
  std::vector<std::string> choices;      ///< Choice
  std::string description;               ///< one line

  bool required() const { return defaultValue.empty() && defaultNote == "required"; }
  /// "(0, 5]", ">= 1", "> 0", "one of: cosine, half_cosine"; empty when any value of the type is valid.
  std::string rangeText() const;
  /// defaultValue, else defaultNote, else "–".
  std::string defaultText() const;
  /// Whether `v` lies in the range (a lower bound 0 exclusive means a positive quantity: isPositiveNormal).
  bool inRange(double v) const;
  /// The one message for a value out of range: "is 0.6; valid: [0, 0.5)".
  std::string rangeMessage(const std::string& shownValue) const;
};

/// The keys of one mapping of the scene, e.g. `materials.NAME (type: membrane)` or `time`.
struct SchemaSection {
  std::string path;         ///< as shown in docs and messages: "time", "meshes.NAME.generator (parafoil)"
  std::string description;  ///< one line
  std::vector<SceneKey> keys;

  const SceneKey& key(const std::string& name) const;  ///< std::logic_error if not declared
  const SceneKey* find(const std::string& name) const;
  std::vector<std::string> names() const;
};

}  // namespace fsi::structure
