#include "structure/scene/SceneSchema.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "structure/model/Error.hpp"
#include "structure/model/PositiveValue.hpp"
#include "structure/scene/JoinNames.hpp"

namespace fsi::structure {

// ---------------------------------------------------------------- SchemaMap

const SceneKey& SchemaMap::declared(const std::string& key, std::initializer_list<KeyType> types) const {
  const SceneKey& k = section_.key(key);
  for (KeyType t : types)
    if (k.type == t) return k;
  throw std::logic_error(fmt::format("scene schema: key '{}' of section '{}' is a {}, not read as such", key,
                                     section_.path, toString(k.type)));
}

bool SchemaMap::has(const std::string& key) const {
  section_.key(key);
  return map_.has(key);
}

void SchemaMap::checkRange(const SceneKey& k, double v, const std::string& shown) const {
  if (!k.inRange(v)) map_.failAt(k.name, k.rangeMessage(shown));
}

namespace {

// The value a key's default stands for (the table is code: a bad default is a programming error).
double defaultNumber(const SceneKey& k, const std::string& section) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(k.defaultValue, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != k.defaultValue.size())
    throw std::logic_error(
        fmt::format("scene schema: key '{}' of section '{}' has no numeric default", k.name, section));
  return v;
}

[[noreturn]] void noDefault(const SceneKey& k, const std::string& section) {
  throw std::logic_error(fmt::format(
      "scene schema: key '{}' of section '{}' has no default: test has() first", k.name, section));
}

std::string shownNumber(const YamlMap& m, const std::string& key) {
  const YAML::Node n = m.node()[key];
  return n && n.IsScalar() ? n.Scalar() : std::string("?");
}

}  // namespace

double SchemaMap::number(const std::string& key) const {
  const SceneKey& k = declared(key, {KeyType::Number});
  if (!map_.has(key)) {
    if (k.required()) map_.required(key);  // the located "missing required key"
    if (k.defaultValue.empty()) noDefault(k, section_.path);
    return defaultNumber(k, section_.path);
  }
  const double v = map_.number(key);
  checkRange(k, v, shownNumber(map_, key));
  return v;
}

std::optional<double> SchemaMap::optionalNumber(const std::string& key) const {
  declared(key, {KeyType::Number});
  if (!map_.has(key)) return std::nullopt;
  return number(key);
}

long SchemaMap::integer(const std::string& key) const {
  const SceneKey& k = declared(key, {KeyType::Integer});
  IntRange r;  // without an upper bound: an int's range, so that the value never wraps when narrowed
  if (k.lower) r.lo = long(std::ceil(k.lower->value + (k.lower->inclusive ? 0.0 : 0.5)));
  if (k.upper && k.upper->value >= kAnyLong.value)
    r.hi = std::numeric_limits<long>::max();
  else if (k.upper)
    r.hi = long(std::floor(k.upper->value - (k.upper->inclusive ? 0.0 : 0.5)));
  if (!map_.has(key)) {
    if (k.required()) map_.required(key);
    if (k.defaultValue.empty()) noDefault(k, section_.path);
    return long(defaultNumber(k, section_.path));
  }
  return map_.integer(key, r);  // the range's message names the bounds from the entry
}

bool SchemaMap::boolean(const std::string& key) const {
  const SceneKey& k = declared(key, {KeyType::Boolean});
  if (!map_.has(key)) {
    if (k.defaultValue == "true" || k.defaultValue == "false") return k.defaultValue == "true";
    if (k.required()) map_.required(key);
    noDefault(k, section_.path);
  }
  return map_.boolean(key, false);
}

std::string SchemaMap::string(const std::string& key) const {
  const SceneKey& k = declared(key, {KeyType::String, KeyType::Choice});
  if (!map_.has(key)) {
    if (k.required()) map_.required(key);
    if (k.defaultValue.empty()) noDefault(k, section_.path);
    return k.defaultValue;
  }
  return k.type == KeyType::Choice ? map_.choice(key, k.choices) : map_.string(key);
}

std::vector<double> SchemaMap::numbers(const std::string& key) const {
  const SceneKey& k = declared(key, {KeyType::Numbers});
  std::vector<double> v = map_.numbers(key);
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!k.inRange(v[i]))
      map_.failAt(key, fmt::format("entry {}: {}", i, k.rangeMessage(fmt::format("{:g}", v[i]))));
  return v;
}

std::array<double, 3> SchemaMap::vec3(const std::string& key) const {
  const SceneKey& k = declared(key, {KeyType::Vec3});
  if (!map_.has(key)) {
    if (k.required()) map_.required(key);
    std::array<double, 3> d{};
    char c1 = 0, c2 = 0, c3 = 0, c4 = 0;
    std::istringstream is(k.defaultValue);
    if (!(is >> c1 >> d[0] >> c2 >> d[1] >> c3 >> d[2] >> c4) || c1 != '[' || c4 != ']')
      noDefault(k, section_.path);
    return d;
  }
  const std::array<double, 3> v = map_.vec3(key);
  for (std::size_t i = 0; i < 3; ++i)
    if (!k.inRange(v[i]))
      map_.failAt(key, fmt::format("component {}: {}", i, k.rangeMessage(fmt::format("{:g}", v[i]))));
  return v;
}

}  // namespace fsi::structure
