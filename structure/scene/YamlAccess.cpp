#include "structure/scene/YamlAccess.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "structure/model/Error.hpp"

namespace fsi::structure {

std::string locate(const std::string& file, const YAML::Node& node, const std::string& path) {
  const YAML::Mark m = node ? node.Mark() : YAML::Mark::null_mark();
  const std::string where = path.empty() ? std::string("(top level)") : path;
  if (m.is_null() || m.line < 0) return fmt::format("{}: {}", file, where);
  return fmt::format("{}:{}:{}: {}", file, m.line + 1, m.column + 1, where);
}

std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t bestD = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const auto& c : candidates) {
    std::vector<std::size_t> prev(c.size() + 1), cur(c.size() + 1);
    for (std::size_t j = 0; j <= c.size(); ++j) prev[j] = j;
    for (std::size_t i = 1; i <= word.size(); ++i) {
      cur[0] = i;
      for (std::size_t j = 1; j <= c.size(); ++j)
        cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (word[i - 1] == c[j - 1] ? 0 : 1)});
      std::swap(prev, cur);
    }
    if (prev[c.size()] < bestD) bestD = prev[c.size()], best = c;
  }
  return best;
}

namespace {
std::string joinKeys(const std::vector<std::string>& keys) {
  std::string s;
  for (const auto& k : keys) s += (s.empty() ? "" : ", ") + k;
  return s;
}
}  // namespace

double asNumber(const YAML::Node& n, const std::string& file, const std::string& path) {
  if (!n.IsScalar()) throw InputError(locate(file, n, path) + ": expected a number");
  double v = 0;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    throw InputError(locate(file, n, path) + fmt::format(": expected a number, got '{}'", n.Scalar()));
  }
  if (!std::isfinite(v)) throw InputError(locate(file, n, path) + ": expected a finite number");
  return v;
}

YamlMap::YamlMap(YAML::Node node, std::string file, std::string path)
    : node_(node), file_(std::move(file)), path_(std::move(path)) {  // YAML::Node is a handle: copies are cheap
  if (!node_ || node_.IsNull()) {
    node_ = YAML::Node(YAML::NodeType::Map);
  } else if (!node_.IsMap()) {
    throw InputError(locate(file_, node_, path_) + ": expected a mapping of keys to values");
  }
}

std::vector<std::string> YamlMap::keys() const {
  std::vector<std::string> k;
  for (const auto& kv : node_) k.push_back(kv.first.as<std::string>());
  return k;
}

bool YamlMap::has(const std::string& key) const {
  return bool(node_[key]);
}

YAML::Node YamlMap::require(const std::string& key) const {
  const YAML::Node n = node_[key];
  if (!n) fail(fmt::format("missing required key '{}'", key));
  used_.insert(key);
  return n;
}

YAML::Node YamlMap::raw(const std::string& key) const {
  used_.insert(key);
  return node_[key];
}

void YamlMap::fail(const std::string& message) const {
  throw InputError(locate(file_, node_, path_) + ": " + message);
}
void YamlMap::failAt(const std::string& key, const std::string& message) const {
  const YAML::Node n = node_[key];
  throw InputError(locate(file_, n ? n : node_, childPath(key)) + ": " + message);
}

double YamlMap::number(const std::string& key) const {
  return asNumber(require(key), file_, childPath(key));
}
double YamlMap::number(const std::string& key, double fallback) const {
  return has(key) ? number(key) : fallback;
}
long YamlMap::integer(const std::string& key) const {
  const YAML::Node n = require(key);
  const double v = asNumber(n, file_, childPath(key));
  if (v != std::floor(v)) failAt(key, fmt::format("expected an integer, got {}", n.Scalar()));
  return long(v);
}
long YamlMap::integer(const std::string& key, long fallback) const {
  return has(key) ? integer(key) : fallback;
}
bool YamlMap::boolean(const std::string& key, bool fallback) const {
  if (!has(key)) return fallback;
  const YAML::Node n = require(key);
  try {
    return n.as<bool>();
  } catch (const YAML::Exception&) {
    failAt(key,
           fmt::format("expected true or false, got '{}'", n.IsScalar() ? n.Scalar() : "(not a scalar)"));
  }
}
std::string YamlMap::string(const std::string& key) const {
  const YAML::Node n = require(key);
  if (!n.IsScalar()) failAt(key, "expected a string");
  return n.Scalar();
}
std::string YamlMap::string(const std::string& key, const std::string& fallback) const {
  return has(key) ? string(key) : fallback;
}
std::string YamlMap::choice(const std::string& key, const std::vector<std::string>& choices) const {
  std::string v = string(key);
  if (std::find(choices.begin(), choices.end(), v) == choices.end()) {
    const std::string near = closestMatch(v, choices);
    failAt(key,
           fmt::format("'{}' is not valid{}; valid choices: {}", v,
                       near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near), joinKeys(choices)));
  }
  return v;
}
std::string YamlMap::choice(const std::string& key, const std::vector<std::string>& choices,
                            const std::string& fallback) const {
  return has(key) ? choice(key, choices) : fallback;
}
std::vector<double> YamlMap::numbers(const std::string& key) const {
  const YAML::Node n = require(key);
  std::vector<double> out;
  if (n.IsScalar()) return {asNumber(n, file_, childPath(key))};
  if (!n.IsSequence()) failAt(key, "expected a number or a list of numbers");
  for (std::size_t i = 0; i < n.size(); ++i)
    out.push_back(asNumber(n[i], file_, fmt::format("{}[{}]", childPath(key), i)));
  return out;
}
std::vector<long> YamlMap::integers(const std::string& key) const {
  std::vector<long> out;
  for (double v : numbers(key)) {
    if (v != std::floor(v)) failAt(key, fmt::format("expected integers, got {}", v));
    out.push_back(long(v));
  }
  return out;
}
std::array<double, 3> YamlMap::vec3(const std::string& key) const {
  const std::vector<double> v = numbers(key);
  if (v.size() != 3) failAt(key, fmt::format("expected 3 numbers [x, y, z], got {}", v.size()));
  return {v[0], v[1], v[2]};
}
std::array<double, 3> YamlMap::vec3(const std::string& key, std::array<double, 3> fallback) const {
  return has(key) ? vec3(key) : fallback;
}
std::vector<std::string> YamlMap::strings(const std::string& key) const {
  const YAML::Node n = require(key);
  if (n.IsScalar()) return {n.Scalar()};
  if (!n.IsSequence()) failAt(key, "expected a string or a list of strings");
  std::vector<std::string> out;
  for (std::size_t i = 0; i < n.size(); ++i) {
    if (!n[i].IsScalar())
      throw InputError(locate(file_, n[i], fmt::format("{}[{}]", childPath(key), i)) + ": expected a string");
    out.push_back(n[i].Scalar());
  }
  return out;
}
YamlMap YamlMap::map(const std::string& key) const {
  return YamlMap(require(key), file_, childPath(key));
}

void YamlMap::finish(const std::vector<std::string>& validKeys) const {
  for (const auto& kv : node_) {
    const std::string k = kv.first.as<std::string>();
    if (used_.count(k)) continue;
    const bool known = std::find(validKeys.begin(), validKeys.end(), k) != validKeys.end();
    const std::string near = closestMatch(k, validKeys);
    throw InputError(locate(file_, kv.first, childPath(k)) +
                     fmt::format(": {} key '{}'{}; valid keys here: {}", known ? "unused" : "unknown", k,
                                 near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near),
                                 joinKeys(validKeys)));
  }
}

namespace {
std::size_t listIndex(const std::string& part, const std::string& assignment) {
  if (part.empty() || part.find_first_not_of("0123456789") != std::string::npos)
    throw InputError(fmt::format("--set '{}': '{}' must be a list index (0, 1, ...)", assignment, part));
  return std::stoul(part);
}
}  // namespace

void applyOverride(YAML::Node& root, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(fmt::format("--set '{}': expected KEY.PATH=VALUE", assignment));
  const std::string path = assignment.substr(0, eq);
  YAML::Node value;
  try {
    value = YAML::Load(assignment.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    throw InputError(fmt::format("--set '{}': value is not valid YAML: {}", assignment, e.what()));
  }
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const auto dot = path.find('.', start);
    parts.push_back(path.substr(start, dot - start));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  // yaml-cpp nodes are handles: walk with copies that reference the same tree.
  std::vector<YAML::Node> chain{root};
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    YAML::Node cur = chain.back();
    const std::string& p = parts[i];
    if (cur.IsSequence()) {
      const std::size_t idx = listIndex(p, assignment);
      if (idx >= cur.size())
        throw InputError(
            fmt::format("--set '{}': index {} out of range (list has {} entries)", path, idx, cur.size()));
      chain.push_back(cur[idx]);
    } else {
      chain.push_back(cur[p]);
    }
  }
  YAML::Node last = chain.back();
  if (last.IsSequence()) {
    const std::size_t idx = listIndex(parts.back(), assignment);
    if (idx >= last.size()) throw InputError(fmt::format("--set '{}': index out of range", path));
    last[idx] = value;
  } else {
    last[parts.back()] = value;
  }
}

}  // namespace fsi::structure
