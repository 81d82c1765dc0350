#include "flight/FlightFile.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "flight/GlideControls.hpp"
#include "structure/model/Error.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::flight {

using structure::YamlMap;

namespace {

constexpr double kDeg = M_PI / 180.0;

Vec3 vec(const YamlMap& m, const std::string& key, const Vec3& fallback) {
  if (!m.has(key)) return fallback;
  const auto v = m.vec3(key);
  return Vec3(v[0], v[1], v[2]);
}

void readSystem(const YamlMap& m, FlightSystem& s) {
  s.mass = m.positive("mass");
  if (m.has("inertia")) {
    const std::vector<double> j = m.numbers("inertia");
    if (j.size() == 3) {
      s.inertia = Vec3(j[0], j[1], j[2]).asDiagonal();
    } else if (j.size() == 6) {  // Ixx, Iyy, Izz, Ixy, Ixz, Iyz
      s.inertia << j[0], j[3], j[4], j[3], j[1], j[5], j[4], j[5], j[2];
    } else {
      m.failAt("inertia", "needs 3 numbers [Ixx, Iyy, Izz] or 6 [Ixx, Iyy, Izz, Ixy, Ixz, Iyz] (kg m^2)");
    }
    Eigen::SelfAdjointEigenSolver<Mat3> eig(s.inertia);
    if (!(eig.eigenvalues().minCoeff() > 0)) m.failAt("inertia", "is not positive definite");
  } else {
    m.failAt("inertia", "is missing: [Ixx, Iyy, Izz] about the mass centre (kg m^2)");
  }
  s.addedMass = vec(m, "added_mass", Vec3::Zero());
  s.addedInertia = vec(m, "added_inertia", Vec3::Zero());
  if (s.addedMass.minCoeff() < 0) m.failAt("added_mass", "must not be negative");
  if (s.addedInertia.minCoeff() < 0) m.failAt("added_inertia", "must not be negative");
  s.canopyPoint = vec(m, "canopy_point", Vec3::Zero());
  s.payloadPoint = vec(m, "payload_point", Vec3::Zero());
  s.payloadDragArea = m.number("payload_drag_area", 0.0);
  s.lineDragArea = m.number("line_drag_area", 0.0);
  if (s.payloadDragArea < 0) m.failAt("payload_drag_area", "must not be negative");
  if (s.lineDragArea < 0) m.failAt("line_drag_area", "must not be negative");
  s.airDensity = m.positive("air_density", s.airDensity);
  s.gravity = m.number("gravity", s.gravity);
  s.munkMoment = m.boolean("munk_moment", s.munkMoment);
  m.finish({"mass", "inertia", "added_mass", "added_inertia", "canopy_point", "payload_point",
            "payload_drag_area", "line_drag_area", "air_density", "gravity", "munk_moment"});
}

void readAero(const YamlMap& m, AeroTable& a) {
  a.area = m.positive("area");
  a.span = m.positive("span");
  a.chord = m.positive("chord");
  for (double deg : m.numbers("alpha")) a.alpha.push_back(deg * kDeg);
  a.CL = m.numbers("CL");
  a.CD = m.numbers("CD");
  a.Cm = m.has("Cm") ? m.numbers("Cm") : std::vector<double>(a.alpha.size(), 0.0);
  a.CL_ds = m.number("CL_brake", 0.0);
  a.CD_ds = m.number("CD_brake", 0.0);
  a.Cm_ds = m.number("Cm_brake", 0.0);
  a.Cm_q = m.number("Cm_q", 0.0);
  a.CY_beta = m.number("CY_beta", 0.0);
  a.Cl_beta = m.number("Cl_beta", 0.0);
  a.Cn_beta = m.number("Cn_beta", 0.0);
  a.Cl_p = m.number("Cl_p", 0.0);
  a.Cn_r = m.number("Cn_r", 0.0);
  a.CY_da = m.number("CY_differential_brake", 0.0);
  a.Cl_da = m.number("Cl_differential_brake", 0.0);
  a.Cn_da = m.number("Cn_differential_brake", 0.0);
  m.finish({"area", "span", "chord", "alpha", "CL", "CD", "Cm", "CL_brake", "CD_brake", "Cm_brake", "Cm_q",
            "CY_beta", "Cl_beta", "Cn_beta", "Cl_p", "Cn_r", "CY_differential_brake", "Cl_differential_brake",
            "Cn_differential_brake"});
  try {
    a.check("aerodynamics");
  } catch (const InputError& e) {
    m.fail(e.what());
  }
}

void readWind(const YamlMap& m, Wind& w) {
  w.steady = vec(m, "steady", Vec3::Zero());
  w.shearPerMetre = vec(m, "shear", Vec3::Zero());
  if (m.has("gust")) {
    const YamlMap g = m.map("gust");
    w.gustPeak = vec(g, "peak", Vec3::Zero());
    w.gustStart = g.number("start", 0.0);
    w.gustDuration = g.positive("duration");
    g.finish({"peak", "start", "duration"});
  }
  m.finish({"steady", "shear", "gust"});
}

void readInitial(const YamlMap& m, FlightState& x) {
  const auto p = m.vec3("position");  // north, east, altitude
  if (!(p[2] >= 0)) m.failAt("position", "altitude (the third number) must not be negative");
  x.position = Vec3(p[0], p[1], -p[2]);
  const double heading = m.number("heading", 0.0) * kDeg;
  const double pitch = m.number("pitch", 0.0) * kDeg;
  x.attitude = Quat(Eigen::AngleAxisd(heading, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY()));
  x.velocity = Vec3(m.positive("airspeed"), 0, 0);
  m.finish({"position", "heading", "pitch", "airspeed"});
}

void readBrakes(const YamlMap& m, BrakeSchedule& b) {
  b.time = m.numbers("time");
  b.left = m.numbers("left");
  b.right = m.numbers("right");
  if (m.has("incidence")) {
    for (double deg : m.numbers("incidence")) b.incidence.push_back(deg * kDeg);
    if (b.incidence.size() != b.time.size())
      m.failAt("incidence", fmt::format("needs one value per 'time' ({}) in degrees", b.time.size()));
    for (double v : b.incidence)
      if (std::abs(v) > 30 * kDeg)
        m.failAt("incidence", "is the rigging's change: at most 30 deg either way");
  }
  m.finish({"time", "left", "right", "incidence"});
  if (b.left.size() != b.time.size() || b.right.size() != b.time.size())
    m.fail(fmt::format("'left' and 'right' need one value per 'time' ({})", b.time.size()));
  for (std::size_t i = 0; i < b.time.size(); ++i) {
    if (i > 0 && !(b.time[i] > b.time[i - 1])) m.failAt("time", "must increase strictly");
    for (const auto* col : {&b.left, &b.right})
      if (!((*col)[i] >= 0 && (*col)[i] <= 1))
        m.fail(fmt::format("brake entry {} is {}; valid: 0 (off) to 1 (full)", i + 1, (*col)[i]));
  }
}

PidGains readGains(const YamlMap& m, const std::string& key, PidGains g) {
  if (!m.has(key)) return g;
  const YamlMap k = m.map(key);
  g.kp = k.number("kp", g.kp);
  g.ki = k.number("ki", g.ki);
  g.kd = k.number("kd", g.kd);
  g.integralLimit = k.positive("integral_limit", g.integralLimit);
  k.finish({"kp", "ki", "kd", "integral_limit"});
  return g;
}

void readGlideSlope(const YamlMap& m, GlideSlopeParams& g) {
  std::vector<std::string> names;
  for (const GlideControlKind& k : glideControlKinds()) names.push_back(k.name);
  g.control = m.choice("control", names);
  const GlideControlKind& kind = *findGlideControl(g.control);
  g.gains = readGains(m, "gains", g.gains);
  g.min = m.number("min", kind.defaultMin);
  g.max = m.number("max", kind.defaultMax);
  g.trim = m.number("trim", 0.5 * (g.min + g.max));
  m.finish({"control", "gains", "trim", "min", "max"});
  for (const auto& [key, v] : {std::pair{"min", g.min}, std::pair{"max", g.max}})
    if (!(v >= kind.lowest && v <= kind.highest))
      m.failAt(key, fmt::format("is {}; valid for {}: {} to {} ({})", v, g.control, kind.lowest, kind.highest,
                                kind.unit));
  if (!(g.min < g.max)) m.failAt("max", "must exceed min");
  if (!(g.trim >= g.min && g.trim <= g.max)) m.failAt("trim", "must lie between min and max");
}

void readMonteCarlo(const YamlMap& m, MonteCarloParams& p) {
  p.runs = int(m.integer("runs", structure::IntRange{1, 100000}));
  p.seed = std::uint64_t(m.integer("seed", 1, structure::IntRange{0, 1000000000000L}));
  auto range = [&](const char* key, std::array<double, 2> fallback, double lo, double hi, const char* unit) {
    if (!m.has(key)) return fallback;
    const std::vector<double> v = m.numbers(key);
    if (v.size() != 2 || !(v[0] <= v[1]) || v[0] < lo || v[1] > hi)
      m.failAt(key, fmt::format("needs [low, high] with {} <= low <= high <= {} ({})", lo, hi, unit));
    return std::array<double, 2>{v[0], v[1]};
  };
  p.windSpeed = range("wind_speed", p.windSpeed, 0, 100, "m/s");
  p.windFrom = range("wind_from", p.windFrom, -360, 720, "deg from north");
  const auto sd = m.vec3("release_sd", p.releaseSd);
  for (double v : sd)
    if (!(v >= 0)) m.failAt("release_sd", "standard deviations [north, east, altitude] must not be negative");
  p.releaseSd = sd;
  m.finish({"runs", "seed", "wind_speed", "wind_from", "release_sd"});
}

void readGuidance(const YamlMap& m, GuidanceParams& g) {
  const YAML::Node list = m.raw("waypoints");
  if (!list.IsSequence() || list.size() == 0)
    m.failAt("waypoints", "needs a list of [north, east] points in metres, the last one the target");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = m.childPath("waypoints") + fmt::format("[{}]", i);
    if (!list[i].IsSequence() || list[i].size() != 2)
      throw InputError(structure::locate(m.file(), list[i], path) +
                       ": a waypoint is [north, east] in metres");
    g.waypoints.push_back({structure::asNumber(list[i][0], m.file(), path + "[0]"),
                           structure::asNumber(list[i][1], m.file(), path + "[1]")});
  }
  g.acceptanceRadius = m.positive("acceptance_radius", g.acceptanceRadius);
  g.course = readGains(m, "course_gains", g.course);
  g.maxYawRate = m.positive("max_yaw_rate", g.maxYawRate);
  g.yawRate = readGains(m, "yaw_rate_gains", g.yawRate);
  g.maxBrake = m.positive("max_brake", g.maxBrake);
  if (g.maxBrake > 1) m.failAt("max_brake", "is a fraction of the full brake: at most 1");
  g.rate = m.positive("rate", g.rate);
  g.rightTurnPullsRight = m.choice("right_turn_brake", {"right", "left"}, "right") == "right";
  if (m.has("glide_slope")) readGlideSlope(m.map("glide_slope"), g.glideSlope);
  m.finish({"waypoints", "acceptance_radius", "course_gains", "max_yaw_rate", "yaw_rate_gains", "max_brake",
            "rate", "right_turn_brake", "glide_slope"});
}

}  // namespace

Controls BrakeSchedule::at(double t) const {
  if (time.empty()) return {};
  const auto inc = [&](std::size_t i) { return incidence.empty() ? 0.0 : incidence[i]; };
  if (t <= time.front()) return {left.front(), right.front(), inc(0)};
  if (t >= time.back()) return {left.back(), right.back(), inc(time.size() - 1)};
  std::size_t i = 1;
  while (time[i] < t) ++i;
  const double s = (t - time[i - 1]) / (time[i] - time[i - 1]);
  return {(1 - s) * left[i - 1] + s * left[i], (1 - s) * right[i - 1] + s * right[i],
          (1 - s) * inc(i - 1) + s * inc(i)};
}

FlightCase readFlightString(const std::string& yaml, const std::string& name,
                            const std::vector<std::string>& overrides) {
  structure::requireUtf8Text(yaml, name);
  YAML::Node root = structure::parseDocument(yaml, name);
  for (const auto& o : overrides) structure::applyOverride(root, o);
  structure::checkDocument(root, name);
  if (!root.IsMap()) throw InputError(fmt::format("{}: a flight file is a mapping of sections", name));
  const YamlMap top(root, name, "");
  FlightCase c;
  c.file = name;
  readSystem(top.map("system"), c.system);
  readAero(top.map("aerodynamics"), c.system.aero);
  if (top.has("wind")) readWind(top.map("wind"), c.wind);
  readInitial(top.map("start"), c.initial);
  if (top.has("brakes")) readBrakes(top.map("brakes"), c.brakes);
  if (top.has("guidance")) {
    if (top.has("brakes")) top.failAt("guidance", "and 'brakes' both set the brakes: keep one");
    readGuidance(top.map("guidance"), c.guidance);
  }
  if (top.has("monte_carlo")) readMonteCarlo(top.map("monte_carlo"), c.monteCarlo);
  if (top.has("time")) {
    const YamlMap t = top.map("time");
    c.endTime = t.positive("end", c.endTime);
    c.step = t.positive("step", c.step);
    c.outputInterval = t.positive("output_interval", c.outputInterval);
    c.stopAtGround = t.boolean("stop_at_ground", c.stopAtGround);
    t.finish({"end", "step", "output_interval", "stop_at_ground"});
    if (c.step > c.outputInterval) t.failAt("step", "must not exceed output_interval");
    if (c.endTime / c.step > 1e8) t.failAt("step", "makes more than 1e8 steps");
  }
  top.finish({"system", "aerodynamics", "wind", "start", "brakes", "guidance", "monte_carlo", "time"});
  return c;
}

FlightCase readFlightFile(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("{}: cannot open the flight file", file.string()));
  std::stringstream ss;
  ss << in.rdbuf();
  return readFlightString(ss.str(), file.string(), overrides);
}

}  // namespace fsi::flight
