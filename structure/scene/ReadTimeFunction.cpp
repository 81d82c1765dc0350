#include "structure/scene/ReadTimeFunction.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "structure/model/Error.hpp"
#include "structure/scene/SceneSchema.hpp"

namespace fsi::structure {

namespace {

constexpr KeyBound kAboveZero{0, false};

SceneKey typeKey(const char* type) {
  return {"type", KeyType::Choice, "", "", "required", {}, {}, {type}, "the function"};
}

}  // namespace

const std::vector<const SchemaSection*>& timeFunctionSchemas() {
  using T = KeyType;
  static const SchemaSection constant{
      "(time function) {type: constant}",
      "f(t) = value (a plain number is the same)",
      {typeKey("constant"), {"value", T::Number, "-", "1.0", "", {}, {}, {}, "the value"}}};
  static const SchemaSection ramp{
      "(time function) {type: ramp | smooth_step}",
      "0 before start, rising to 1 over duration (linearly, or as a smooth step), then 1",
      {{"type", T::Choice, "", "", "required", {}, {}, {"ramp", "smooth_step"}, "the function"},
       {"duration", T::Number, "s", "", "required", kAboveZero, {}, {}, "the rise time"},
       {"start", T::Number, "s", "0.0", "", {}, {}, {}, "when it starts rising"}}};
  static const SchemaSection sine{
      "(time function) {type: sine}",
      "offset + amplitude sin(2π frequency t + phase)",
      {typeKey("sine"),
       {"amplitude", T::Number, "-", "", "required", {}, {}, {}, "the amplitude"},
       {"frequency", T::Number, "Hz", "", "required", {}, {}, {}, "the frequency"},
       {"phase", T::Number, "rad", "0.0", "", {}, {}, {}, "the phase"},
       {"offset", T::Number, "-", "0.0", "", {}, {}, {}, "the offset"}}};
  static const SchemaSection table{"(time function) {type: table}",
                                   "linear between the points, constant beyond them",
                                   {typeKey("table"),
                                    {"points",
                                     T::Any,
                                     "",
                                     "",
                                     "required",
                                     {},
                                     {},
                                     {},
                                     "[[t0, v0], [t1, v1], ...], times strictly increasing"}}};
  static const std::vector<const SchemaSection*> all{&constant, &ramp, &sine, &table};
  return all;
}

TimeFunction readTimeFunction(const YamlMap& parent, const std::string& key) {
  if (!parent.has(key)) return TimeFunction::constant(1.0);
  const YAML::Node raw = parent.raw(key);
  if (raw.IsScalar()) return TimeFunction::constant(asNumber(raw, parent.file(), parent.childPath(key)));
  YamlMap m(raw, parent.file(), parent.childPath(key));
  const std::string type = m.choice("type", {"constant", "ramp", "smooth_step", "table", "sine"});
  try {
    const auto& schemas = timeFunctionSchemas();
    if (type == "constant") {
      const SchemaMap c(m, *schemas[0]);
      const double v = c.number("value");
      c.finish();
      return TimeFunction::constant(v);
    }
    if (type == "ramp" || type == "smooth_step") {
      const SchemaMap r(m, *schemas[1]);
      const double d = r.number("duration"), s = r.number("start");
      r.finish();
      return type == "ramp" ? TimeFunction::ramp(d, s) : TimeFunction::smoothStep(d, s);
    }
    if (type == "sine") {
      const SchemaMap w(m, *schemas[2]);
      const double a = w.number("amplitude"), f = w.number("frequency"), ph = w.number("phase"),
                   off = w.number("offset");
      w.finish();
      return TimeFunction::sine(a, f, ph, off);
    }
    const YAML::Node pts = m.raw("points");
    if (!pts || !pts.IsSequence() || pts.size() == 0)
      m.fail("a table needs 'points: [[t0, v0], [t1, v1], ...]'");
    std::vector<std::pair<double, double>> p;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const std::string pp = fmt::format("{}.points[{}]", m.path(), i);
      if (!pts[i].IsSequence() || pts[i].size() != 2)
        throw InputError(locate(m.file(), pts[i], pp) + ": expected [time, value]");
      p.emplace_back(asNumber(pts[i][0], m.file(), pp), asNumber(pts[i][1], m.file(), pp));
    }
    SchemaMap(m, *schemas[3]).finish();
    for (std::size_t i = 1; i < p.size(); ++i)
      if (!(p[i].first > p[i - 1].first)) m.failAt("points", "times must strictly increase");
    return TimeFunction::table(std::move(p));
  } catch (const std::invalid_argument& e) {
    m.fail(e.what());
  }
}

}  // namespace fsi::structure
