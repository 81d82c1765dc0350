#include "structure/scene/YamlAccess.hpp"

#include <fmt/format.h>
#include <yaml-cpp/depthguard.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <unordered_map>

#include "structure/model/Error.hpp"

namespace fsi::structure {

std::string locate(const std::string& file, const YAML::Node& node, const std::string& path) {
  const YAML::Mark m = node ? node.Mark() : YAML::Mark::null_mark();
  const std::string where = path.empty() ? std::string("(top level)") : path;
  if (m.is_null() || m.line < 0) return fmt::format("{}: {}", file, where);
  return fmt::format("{}:{}:{}: {}", file, m.line + 1, m.column + 1, where);
}

namespace {
std::string joinKeys(const std::vector<std::string>& keys) {
  std::string s;
  for (const auto& k : keys) s += (s.empty() ? "" : ", ") + k;
  return s;
}

// yaml-cpp refuses a number that overflows a double with a bare "bad conversion"; this tells the two apart.
bool overflowsDouble(const std::string& s) {
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  return !s.empty() && end == s.c_str() + s.size() && errno == ERANGE && std::abs(v) > 1.0;
}

bool isIntegerLiteral(const std::string& s) {
  const std::size_t digits = (!s.empty() && (s[0] == '+' || s[0] == '-')) ? 1 : 0;
  return s.size() > digits && s.find_first_not_of("0123456789", digits) == std::string::npos;
}

std::string describe(IntRange r) {
  if (r.hi == std::numeric_limits<long>::max()) return fmt::format("an integer >= {}", r.lo);
  return fmt::format("an integer from {} to {}", r.lo, r.hi);
}

// yaml-cpp's tags: "?" for a plain scalar (and an untagged collection), "!" for a quoted one, the core
// tags spelt out ("tag:yaml.org,2002:str" for `!!str`).
const std::string kCoreTag = "tag:yaml.org,2002:";

std::string shownTag(const std::string& tag) {
  return tag.rfind(kCoreTag, 0) == 0 ? "!!" + tag.substr(kCoreTag.size()) : tag;
}

// The rule for scalars (docs/SCENES.md, "Errors"): a value's YAML type must be the key's. A number, an
// integer or a boolean is written plain (or tagged `!!float`, `!!int`, `!!bool`); a quoted scalar or one
// tagged
// `!!str` is text and is refused where a number or a boolean is expected; null is never a value.
enum class Expected { number, integer, boolean, text };

const char* expectedName(Expected e) {
  switch (e) {
    case Expected::number:
      return "a number";
    case Expected::integer:
      return "an integer";
    case Expected::boolean:
      return "true or false";
    case Expected::text:
      return "a string";
  }
  return "a value";
}

void checkScalar(const YAML::Node& n, const std::string& file, const std::string& path, Expected e) {
  if (isNullValue(n))
    throw InputError(locate(file, n, path) +
                     fmt::format(": no value given (empty or null); expected {}", expectedName(e)));
  if (!n.IsScalar()) throw InputError(locate(file, n, path) + fmt::format(": expected {}", expectedName(e)));
  const std::string& tag = n.Tag();
  if (tag == "?") return;
  const bool text = tag == "!" || tag == kCoreTag + "str";
  if (e == Expected::text) {
    if (!text)
      throw InputError(locate(file, n, path) +
                       fmt::format(": expected a string, but '{}' is tagged {}", n.Scalar(), shownTag(tag)));
    return;
  }
  if (text)
    throw InputError(locate(file, n, path) +
                     fmt::format(": expected {}, got the string '{}' ({}); write it without quotes or tag",
                                 expectedName(e), n.Scalar(), tag == "!" ? "quoted" : "tagged !!str"));
  const bool fits = e == Expected::boolean ? tag == kCoreTag + "bool"
                                           : tag == kCoreTag + "float" || tag == kCoreTag + "int";
  if (!fits)
    throw InputError(locate(file, n, path) + fmt::format(": expected {}, but '{}' is tagged {}",
                                                         expectedName(e), n.Scalar(), shownTag(tag)));
}

[[noreturn]] void outOfRange(const YAML::Node& n, const std::string& file, const std::string& path,
                             IntRange r) {
  throw InputError(locate(file, n, path) +
                   fmt::format(": {} is out of range; expected {}", n.Scalar(), describe(r)));
}

}  // namespace

bool isNullValue(const YAML::Node& n) {
  return !n || n.IsNull() || n.Tag() == "tag:yaml.org,2002:null";
}

double asNumber(const YAML::Node& n, const std::string& file, const std::string& path) {
  checkScalar(n, file, path, Expected::number);
  double v = 0;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    if (overflowsDouble(n.Scalar()))
      throw InputError(
          locate(file, n, path) +
          fmt::format(": {} is out of range (numbers must be below about 1.8e308 in magnitude)", n.Scalar()));
    throw InputError(locate(file, n, path) + fmt::format(": expected a number, got '{}'", n.Scalar()));
  }
  if (!std::isfinite(v))
    throw InputError(locate(file, n, path) + fmt::format(": expected a finite number, got '{}'", n.Scalar()));
  if (n.Tag() == "tag:yaml.org,2002:int" && v != std::floor(v))
    throw InputError(locate(file, n, path) +
                     fmt::format(": '{}' is tagged !!int but is not an integer", n.Scalar()));
  return v;
}

double asPositive(const YAML::Node& n, const std::string& file, const std::string& path) {
  const double v = asNumber(n, file, path);
  if (!isPositiveNormal(v))
    throw InputError(locate(file, n, path) + fmt::format(": {}; got {}", kPositiveRule, n.Scalar()));
  return v;
}

long asInteger(const YAML::Node& n, const std::string& file, const std::string& path, IntRange range) {
  checkScalar(n, file, path, Expected::integer);
  const std::string& s = n.Scalar();
  long long v = 0;
  if (isIntegerLiteral(s)) {
    // Parsed as an integer, not through double, so that large values stay exact.
    errno = 0;
    v = std::strtoll(s.c_str(), nullptr, 10);
    if (errno == ERANGE) outOfRange(n, file, path, range);
  } else {
    const double d = asNumber(n, file, path);  // also accepts integral numbers such as 1e3
    if (d != std::floor(d))
      throw InputError(locate(file, n, path) + fmt::format(": expected an integer, got {}", s));
    if (std::abs(d) > 9007199254740992.0)
      outOfRange(n, file, path, range);  // beyond 2^53 a double is inexact
    v = static_cast<long long>(d);
  }
  if (v < range.lo || v > range.hi) outOfRange(n, file, path, range);
  return long(v);
}

// ---------------------------------------------------------------- whole-document checks
namespace {

// A scene nests fewer than 10 levels and yaml-cpp's parser stops at about 500, but aliases can chain nested
// anchors to any depth, which would overflow the stack of every recursive reader.
constexpr int kMaxDepth = 500;
constexpr std::size_t kMaxValues = 20'000'000;  // keys and values after alias expansion

// Offset of the first byte that does not belong to a valid UTF-8 sequence (no overlong forms, no
// surrogates, nothing above U+10FFFF: what the JSON writer of summary.json accepts), or npos.
std::size_t invalidUtf8At(const std::string& s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      ++i;
      continue;
    }
    std::size_t len = 0;
    std::uint32_t cp = 0, min = 0;
    if ((c & 0xE0) == 0xC0) {
      len = 2, cp = c & 0x1F, min = 0x80;
    } else if ((c & 0xF0) == 0xE0) {
      len = 3, cp = c & 0x0F, min = 0x800;
    } else if ((c & 0xF8) == 0xF0) {
      len = 4, cp = c & 0x07, min = 0x10000;
    } else {
      return i;
    }
    if (i + len > s.size()) return i;
    for (std::size_t k = 1; k < len; ++k) {
      const auto d = static_cast<unsigned char>(s[i + k]);
      if ((d & 0xC0) != 0x80) return i;
      cp = (cp << 6) | (d & 0x3F);
    }
    if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return i;
    i += len;
  }
  return std::string::npos;
}

class DocumentChecker {
 public:
  explicit DocumentChecker(const std::string& file) : file_(file) {}

  struct Extent {
    std::size_t values = 1;  ///< keys and values below and including the node, aliases expanded
    int height = 0;          ///< levels below the node
  };

  Extent check(const YAML::Node& n, const std::string& path, int depth) {
    if (depth > kMaxDepth) fail(n, path, fmt::format("nested more than {} levels deep", kMaxDepth));
    checkTag(n, path);
    if (n.IsScalar()) {
      checkText(n.Scalar(), n, path, "text");
      return {};
    }
    if (!n.IsSequence() && !n.IsMap()) return {};
    // An alias is the same node as its anchor: a container seen before is not walked again, which keeps
    // "billion laughs" documents cheap here while their expanded size is still counted and limited.
    if (const Extent* e = known(n)) {
      if (depth + e->height > kMaxDepth)
        fail(n, path, fmt::format("nested more than {} levels deep", kMaxDepth));
      return *e;
    }
    for (const YAML::Node& open : open_)
      if (open.is(n)) fail(n, path, "an alias refers to a node that contains it (a cycle)");
    open_.push_back(n);
    Extent total;
    const auto add = [&](const Extent& e) {
      total.values = std::min(total.values + e.values, kMaxValues + 1);
      total.height = std::max(total.height, e.height + 1);
    };
    if (n.IsSequence()) {
      std::size_t i = 0;
      for (const auto& child : n) {
        const std::string entry = fmt::format("{}[{}]", path, i++);
        // No list of a scene holds nulls: refused here, where the entry still has its place in the file
        // (a reader would see an empty mapping or selector without one).
        if (isNullValue(child)) fail(child, entry, "a list entry has no value (empty or null)");
        add(check(child, entry, depth + 1));
      }
    } else {
      std::unordered_map<std::string, YAML::Mark> seen;
      for (const auto& kv : n) {
        const YAML::Node& key = kv.first;
        if (!key.IsScalar())
          fail(key, path,
               key.IsNull() ? "empty or null key" : "a key must be a plain name, not a list or a mapping");
        const std::string& k = key.Scalar();
        const std::string child = path.empty() ? k : path + "." + k;
        checkText(k, key, path, "key");
        const auto [first, fresh] = seen.emplace(k, key.Mark());
        if (!fresh) {
          const YAML::Mark& m = first->second;
          fail(key, child,
               fmt::format("duplicate key '{}' ({}); a key may appear only once in a mapping", k,
                           m.is_null() || m.line < 0
                               ? std::string("given before")
                               : fmt::format("first at line {}, column {}", m.line + 1, m.column + 1)));
        }
        add({});
        add(check(kv.second, child, depth + 1));
      }
    }
    open_.pop_back();
    if (total.values > kMaxValues)
      fail(n, path, fmt::format("expands to more than {} keys and values (through aliases?)", kMaxValues));
    done_[n.Mark().pos].push_back({n, total});
    return total;
  }

 private:
  [[noreturn]] void fail(const YAML::Node& n, const std::string& path, const std::string& message) const {
    throw InputError(locate(file_, n, path) + ": " + message);
  }

  // Tags: only YAML's core tags, each on a node of its kind (`!!map` on a mapping, `!!seq` on a list, the
  // scalar ones on scalars, `!!null` on an empty one); whether a scalar's tag fits its key is checked when
  // the key is read. Anything else (`!foo`, `!!binary`, `!!timestamp`) would be silently read as plain text.
  void checkTag(const YAML::Node& n, const std::string& path) const {
    const std::string& tag = n.Tag();
    if (tag.empty() || tag == "?" || tag == "!") return;
    const std::string core = "tag:yaml.org,2002:";
    const std::string name = tag.rfind(core, 0) == 0 ? tag.substr(core.size()) : std::string();
    const bool scalarTag =
        name == "str" || name == "int" || name == "float" || name == "bool" || name == "null";
    if (!scalarTag && name != "map" && name != "seq")
      fail(n, path,
           fmt::format("the tag '{}' is not supported; use plain values (or the core tags !!str, !!int, "
                       "!!float, !!bool where they match the key)",
                       name.empty() ? tag : "!!" + name));
    const bool fits = n.IsMap() ? name == "map" : n.IsSequence() ? name == "seq" : scalarTag;
    if (!fits)
      fail(n, path,
           fmt::format("the tag !!{} does not fit a {}", name,
                       n.IsMap()        ? "mapping"
                       : n.IsSequence() ? "list"
                                        : "plain value"));
    if (name == "null" && n.IsScalar() && !n.Scalar().empty())
      fail(n, path, fmt::format("'{}' is tagged !!null, which is no value", n.Scalar()));
  }

  void checkText(const std::string& s, const YAML::Node& n, const std::string& path, const char* what) const {
    const std::size_t bad = invalidUtf8At(s);
    if (bad != std::string::npos)
      fail(n, path,
           fmt::format("{} is not valid UTF-8 (byte 0x{:02X} at position {}); save the file as UTF-8", what,
                       static_cast<unsigned>(static_cast<unsigned char>(s[bad])), bad));
  }

  const Extent* known(const YAML::Node& n) const {
    const auto it = done_.find(n.Mark().pos);
    if (it == done_.end()) return nullptr;
    for (const auto& [node, extent] : it->second)
      if (node.is(n)) return &extent;
    return nullptr;
  }

  const std::string& file_;
  std::unordered_map<int, std::vector<std::pair<YAML::Node, Extent>>> done_;  // by position, then identity
  std::vector<YAML::Node> open_;  // containers on the current path
};

}  // namespace

void requireUtf8Text(const std::string& text, const std::string& file) {
  // A YAML stream is UTF-8 text (comments too): refuse any other bytes where they are, before parsing.
  const std::size_t bad = invalidUtf8At(text);
  if (bad != std::string::npos) {
    const std::size_t lineStart = text.rfind('\n', bad == 0 ? 0 : bad - 1);
    const std::size_t line =
        1 + std::size_t(std::count(text.begin(), text.begin() + std::ptrdiff_t(bad), '\n'));
    const std::size_t col = lineStart == std::string::npos || bad == 0 ? bad + 1 : bad - lineStart;
    throw InputError(fmt::format("{}:{}:{}: the file is not valid UTF-8 (byte 0x{:02X}); save it as UTF-8",
                                 file, line, col,
                                 static_cast<unsigned>(static_cast<unsigned char>(text[bad]))));
  }
}

YAML::Node parseDocument(const std::string& text, const std::string& file) {
  std::vector<YAML::Node> docs;
  try {
    docs = YAML::LoadAll(text);
  } catch (const YAML::DeepRecursion& e) {  // its own message is "bad file"
    throw InputError(fmt::format("{}:{}:{}: nested too deeply ({} levels)", file, e.mark.line + 1,
                                 e.mark.column + 1, e.depth()));
  } catch (const YAML::ParserException& e) {
    if (e.mark.is_null() || e.mark.line < 0)
      throw InputError(fmt::format("{}: YAML syntax error: {}", file, e.msg));
    throw InputError(
        fmt::format("{}:{}:{}: YAML syntax error: {}", file, e.mark.line + 1, e.mark.column + 1, e.msg));
  } catch (const YAML::Exception& e) {
    throw InputError(fmt::format("{}: YAML error: {}", file, e.what()));
  }
  // yaml-cpp's Load() would silently drop everything after a '---'; an empty trailing document is harmless.
  for (std::size_t i = 1; i < docs.size(); ++i)
    if (!docs[i].IsNull())
      throw InputError(locate(file, docs[i], "") +
                       ": a second YAML document starts here (after '---' or '...'); the file must hold one");
  return docs.empty() ? YAML::Node() : docs.front();
}

void checkDocument(const YAML::Node& root, const std::string& file) {
  DocumentChecker(file).check(root, "", 0);
}

YamlMap::YamlMap(YAML::Node node, std::string file, std::string path)
    : node_(node),
      file_(std::move(file)),
      path_(std::move(path)) {      // YAML::Node is a handle: copies are cheap
  if (node_) origin_.reset(node_);  // reset: Node::operator= would assign into the referenced node
  if (!node_ || node_.IsNull()) {
    node_ = YAML::Node(YAML::NodeType::Map);
  } else if (!node_.IsMap()) {
    throw InputError(locate(file_, node_, path_) + ": expected a mapping of keys to values");
  }
}

std::vector<std::string> YamlMap::keys() const {
  std::vector<std::string> k;
  for (const auto& kv : node_) {
    if (!kv.first.IsScalar())
      throw InputError(locate(file_, kv.first, path_) + ": a key must be a plain name");
    k.push_back(kv.first.Scalar());
  }
  return k;
}

bool YamlMap::has(const std::string& key) const {
  return bool(node_[key]);
}

YAML::Node YamlMap::require(const std::string& key) const {
  const YAML::Node n = node_[key];
  if (!n) {
    // A key the map has that is close to the missing one is most likely it, misspelt: say so.
    std::string near;
    if (node_.IsMap())
      for (const auto& kv : node_) {
        const std::string k = kv.first.IsScalar() ? kv.first.Scalar() : std::string();
        if (!k.empty() && closestMatch(k, {key}) == key) near = k;
      }
    fail(fmt::format("missing required key '{}'{}", key,
                     near.empty() ? "" : fmt::format(" (found '{}': did you mean '{}'?)", near, key)));
  }
  used_.insert(key);
  return n;
}

YAML::Node YamlMap::required(const std::string& key) const {
  const YAML::Node n = require(key);
  if (isNullValue(n)) {
    // `nodes:` with nothing after it: a null value has no place in the file of its own, so name its key's.
    YAML::Node where = node_;
    for (const auto& kv : node_)
      if (kv.first.IsScalar() && kv.first.Scalar() == key) where.reset(kv.first);
    throw InputError(locate(file_, where, childPath(key)) + ": no value given");
  }
  return n;
}

YAML::Node YamlMap::raw(const std::string& key) const {
  used_.insert(key);
  return node_[key];
}

void YamlMap::fail(const std::string& message) const {
  // An empty value (`probes: {p: }`) became an empty map without a place in the file: locate it by the
  // value as it was read.
  const bool placed = node_ && !node_.Mark().is_null();
  throw InputError(locate(file_, placed || !origin_ ? node_ : origin_, path_) + ": " + message);
}
void YamlMap::failAt(const std::string& key, const std::string& message) const {
  const YAML::Node n = node_[key];
  throw InputError(locate(file_, n ? n : node_, childPath(key)) + ": " + message);
}

double YamlMap::number(const std::string& key) const {
  return asNumber(required(key), file_, childPath(key));
}
double YamlMap::number(const std::string& key, double fallback) const {
  return has(key) ? number(key) : fallback;
}
double YamlMap::positive(const std::string& key) const {
  return asPositive(required(key), file_, childPath(key));
}
double YamlMap::positive(const std::string& key, double fallback) const {
  return has(key) ? positive(key) : fallback;
}
long YamlMap::integer(const std::string& key, IntRange range) const {
  return asInteger(required(key), file_, childPath(key), range);
}
long YamlMap::integer(const std::string& key, long fallback, IntRange range) const {
  return has(key) ? integer(key, range) : fallback;
}
bool YamlMap::boolean(const std::string& key, bool fallback) const {
  if (!has(key)) return fallback;
  const YAML::Node n = required(key);
  checkScalar(n, file_, childPath(key), Expected::boolean);
  try {
    return n.as<bool>();
  } catch (const YAML::Exception&) {
    failAt(key,
           fmt::format("expected true or false, got '{}'", n.IsScalar() ? n.Scalar() : "(not a scalar)"));
  }
}
std::string YamlMap::string(const std::string& key) const {
  const YAML::Node n = required(key);
  checkScalar(n, file_, childPath(key), Expected::text);
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
  const YAML::Node n = required(key);
  std::vector<double> out;
  if (n.IsScalar()) return {asNumber(n, file_, childPath(key))};
  if (!n.IsSequence()) failAt(key, "expected a number or a list of numbers");
  for (std::size_t i = 0; i < n.size(); ++i)
    out.push_back(asNumber(n[i], file_, fmt::format("{}[{}]", childPath(key), i)));
  return out;
}
std::vector<long> YamlMap::integers(const std::string& key, IntRange range) const {
  const YAML::Node n = required(key);
  if (n.IsScalar()) return {asInteger(n, file_, childPath(key), range)};
  if (!n.IsSequence()) failAt(key, "expected an integer or a list of integers");
  std::vector<long> out;
  for (std::size_t i = 0; i < n.size(); ++i)
    out.push_back(asInteger(n[i], file_, fmt::format("{}[{}]", childPath(key), i), range));
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
  const YAML::Node n = required(key);
  if (n.IsScalar()) return {string(key)};
  if (!n.IsSequence()) failAt(key, "expected a string or a list of strings");
  std::vector<std::string> out;
  for (std::size_t i = 0; i < n.size(); ++i) {
    checkScalar(n[i], file_, fmt::format("{}[{}]", childPath(key), i), Expected::text);
    out.push_back(n[i].Scalar());
  }
  return out;
}
YamlMap YamlMap::map(const std::string& key) const {
  YamlMap child(require(key), file_, childPath(key));
  if (child.node_.Mark().is_null())
    // An empty value (`generator:`) has no place in the file of its own: messages point at its key.
    for (const auto& kv : node_)
      if (kv.first.IsScalar() && kv.first.Scalar() == key) child.origin_.reset(kv.first);
  return child;
}

void YamlMap::finish(const std::vector<std::string>& validKeys) const {
  for (const auto& kv : node_) {
    if (!kv.first.IsScalar())
      throw InputError(locate(file_, kv.first, path_) + ": a key must be a plain name");
    const std::string k = kv.first.Scalar();
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

std::string shown(const std::string& walked) {
  return walked.empty() ? std::string("(top level)") : walked;
}

std::size_t listIndex(const std::string& part, std::size_t size, const std::string& walked,
                      const std::string& assignment) {
  if (part.find_first_not_of("0123456789") != std::string::npos)
    throw InputError(fmt::format("--set '{}': '{}' is a list, so '{}' must be an index (0, 1, ...)",
                                 assignment, shown(walked), part));
  std::size_t idx = 0;
  bool tooLarge = false;
  for (const char c : part) {
    if (idx > (std::numeric_limits<std::size_t>::max() - 9) / 10) {
      tooLarge = true;
      break;
    }
    idx = 10 * idx + std::size_t(c - '0');
  }
  if (tooLarge || idx >= size)
    throw InputError(fmt::format("--set '{}': index {} is out of range; {}", assignment, part,
                                 size == 0
                                     ? fmt::format("'{}' is an empty list", shown(walked))
                                     : fmt::format("'{}' has indices 0 to {}", shown(walked), size - 1)));
  return idx;
}

// One step along a --set path: a list by index, a mapping (or an absent or empty value, which becomes one)
// by key. A scalar has no keys: yaml-cpp would throw a bare exception there, and it would silently turn a
// list into a mapping, so both are checked first.
YAML::Node child(YAML::Node cur, const std::string& part, const std::string& walked,
                 const std::string& assignment) {
  if (cur.IsSequence()) return cur[listIndex(part, cur.size(), walked, assignment)];
  if (cur.IsScalar())
    throw InputError(fmt::format("--set '{}': '{}' is a value ('{}'), not a mapping, so it has no key '{}'",
                                 assignment, shown(walked), cur.Scalar(), part));
  return cur[part];
}

}  // namespace

void applyOverride(YAML::Node& root, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(fmt::format("--set '{}': expected KEY.PATH=VALUE", assignment));
  const std::string path = assignment.substr(0, eq);
  YAML::Node value;
  try {
    value = parseDocument(assignment.substr(eq + 1), "value");
  } catch (const InputError& e) {
    throw InputError(fmt::format("--set '{}': the value is not valid YAML: {}", assignment, e.what()));
  }
  if (isNullValue(value))
    throw InputError(fmt::format("--set '{}': no value after '=' (empty or null); give one, e.g. {}=1",
                                 assignment, assignment.substr(0, eq)));
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const auto dot = path.find('.', start);
    parts.push_back(path.substr(start, dot - start));
    if (parts.back().empty())
      throw InputError(fmt::format("--set '{}': empty key in '{}' (a dot at the start or end, or two dots)",
                                   assignment, path));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  // yaml-cpp nodes are handles, and assigning one node to another changes the tree: walk with copies.
  std::vector<YAML::Node> chain{root};
  std::string walked;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    chain.push_back(child(chain.back(), parts[i], walked, assignment));
    walked += (walked.empty() ? "" : ".") + parts[i];
  }
  child(chain.back(), parts.back(), walked, assignment) = value;
}

}  // namespace fsi::structure
