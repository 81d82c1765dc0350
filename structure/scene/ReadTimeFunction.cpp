#include "structure/scene/ReadTimeFunction.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "structure/model/Error.hpp"

namespace fsi::structure {

TimeFunction readTimeFunction(const YamlMap& parent, const std::string& key) {
  if (!parent.has(key)) return TimeFunction::constant(1.0);
  const YAML::Node raw = parent.raw(key);
  if (raw.IsScalar()) return TimeFunction::constant(asNumber(raw, parent.file(), parent.childPath(key)));
  YamlMap m(raw, parent.file(), parent.childPath(key));
  const std::string type = m.choice("type", {"constant", "ramp", "smooth_step", "table", "sine"});
  try {
    if (type == "constant") {
      const double v = m.number("value", 1.0);
      m.finish({"type", "value"});
      return TimeFunction::constant(v);
    }
    if (type == "ramp" || type == "smooth_step") {
      const double d = m.number("duration"), s = m.number("start", 0.0);
      m.finish({"type", "duration", "start"});
      if (!isPositiveNormal(d)) m.failAt("duration", kPositiveRule);
      return type == "ramp" ? TimeFunction::ramp(d, s) : TimeFunction::smoothStep(d, s);
    }
    if (type == "sine") {
      const double a = m.number("amplitude"), f = m.number("frequency"), ph = m.number("phase", 0.0),
                   off = m.number("offset", 0.0);
      m.finish({"type", "amplitude", "frequency", "phase", "offset"});
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
    m.finish({"type", "points"});
    for (std::size_t i = 1; i < p.size(); ++i)
      if (!(p[i].first > p[i - 1].first)) m.failAt("points", "times must strictly increase");
    return TimeFunction::table(std::move(p));
  } catch (const std::invalid_argument& e) {
    m.fail(e.what());
  }
}

}  // namespace fsi::structure
