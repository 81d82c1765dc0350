#include "structure/model/SchemaKey.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "structure/model/PositiveValue.hpp"

namespace fsi::structure {

const char* toString(KeyType t) {
  switch (t) {
    case KeyType::Number:
      return "number";
    case KeyType::Integer:
      return "integer";
    case KeyType::Boolean:
      return "boolean";
    case KeyType::String:
      return "string";
    case KeyType::Choice:
      return "choice";
    case KeyType::Vec3:
      return "[x, y, z]";
    case KeyType::Numbers:
      return "number(s)";
    case KeyType::Strings:
      return "string(s)";
    case KeyType::Map:
      return "mapping";
    case KeyType::Selector:
      return "selector";
    case KeyType::Any:
      return "see text";
  }
  return "value";
}

// ---------------------------------------------------------------- SceneKey

namespace {

bool positiveLower(const SceneKey& k) {
  return k.lower && k.lower->value == 0 && !k.lower->inclusive;
}

}  // namespace

namespace {

bool noUpper(const SceneKey& k) {
  return !k.upper || k.upper->value >= kAnyLong.value;
}

}  // namespace

std::string SceneKey::rangeText() const {
  if (type == KeyType::Integer && !upper) {  // read into an int (SchemaMap::integer)
    SceneKey bounded = *this;
    bounded.upper = KeyBound{2147483647.0, true};
    return bounded.rangeText();
  }
  if (type == KeyType::Choice) {
    std::string s = "one of: ";
    for (std::size_t i = 0; i < choices.size(); ++i) s += (i ? ", " : "") + choices[i];
    return s;
  }
  if (lower && !noUpper(*this))
    return fmt::format("{}{}, {}{}", lower->inclusive ? "[" : "(", lower->value, upper->value,
                       upper->inclusive ? "]" : ")");
  if (lower) return fmt::format("{} {}", lower->inclusive ? ">=" : ">", lower->value);
  if (!noUpper(*this)) return fmt::format("{} {}", upper->inclusive ? "<=" : "<", upper->value);
  return "";
}

std::string SceneKey::defaultText() const {
  if (!defaultValue.empty()) return defaultValue;
  if (!defaultNote.empty()) return defaultNote;
  return "–";
}

bool SceneKey::inRange(double v) const {
  if (!std::isfinite(v)) return false;
  if (positiveLower(*this) && !isPositiveNormal(v)) return false;
  if (lower && (lower->inclusive ? v < lower->value : v <= lower->value)) return false;
  if (upper && (upper->inclusive ? v > upper->value : v >= upper->value)) return false;
  return true;
}

std::string SceneKey::rangeMessage(const std::string& shownValue) const {
  // A positive quantity (an open bound at 0) is under the scene's one rule for those (isPositiveNormal).
  if (positiveLower(*this) && !upper) return fmt::format("{}; got {}", kPositiveRule, shownValue);
  const double v = std::strtod(shownValue.c_str(), nullptr);
  const bool subnormal = positiveLower(*this) && v > 0 && !isPositiveNormal(v);
  return fmt::format("is {}; valid: {}{}", shownValue, rangeText(),
                     subnormal ? " (and at least 2.2e-308: a smaller, subnormal value underflows)" : "");
}

// ---------------------------------------------------------------- SchemaSection

const SceneKey* SchemaSection::find(const std::string& name) const {
  for (const SceneKey& k : keys)
    if (k.name == name) return &k;
  return nullptr;
}

const SceneKey& SchemaSection::key(const std::string& name) const {
  const SceneKey* k = find(name);
  if (!k) throw std::logic_error(fmt::format("scene schema: section '{}' declares no key '{}'", path, name));
  return *k;
}

std::vector<std::string> SchemaSection::names() const {
  std::vector<std::string> n;
  n.reserve(keys.size());
  for (const SceneKey& k : keys) n.push_back(k.name);
  return n;
}

}  // namespace fsi::structure
