#include "flight/FlightRun.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

#include "structure/model/Error.hpp"

namespace fsi::flight {

namespace {

constexpr double kDeg = 180.0 / M_PI;

bool finite(const FlightState& x) {
  return x.position.allFinite() && x.velocity.allFinite() && x.rates.allFinite() &&
         x.attitude.coeffs().allFinite();
}

/// Roll, pitch, yaw [deg] (the aerospace sequence: yaw about z, pitch about y, roll about x).
Vec3 eulerDeg(const Quat& q) {
  const Mat3 r = q.toRotationMatrix();
  const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  return Vec3(std::atan2(r(2, 1), r(2, 2)), pitch, std::atan2(r(1, 0), r(0, 0))) * kDeg;
}

void writeCsvRow(std::ofstream& csv, const FlightRow& r) {
  const Vec3& f = r.aeroForce;
  csv << fmt::format(
      "{:.6f},{:.6f},{:.6f},{:.6f},{:.5f},{:.5f},{:.5f},{:.6f},{:.5f},{:.5f},{:.6f},{:.6f},{:.6f},{:.6f},"
      "{:.6f},{:.4f},{:.4f},{:.6f},{:.6f},{:.6f},{:.5f},{:.5f},{:.6f},{:.6f},{:.6f}\n",
      r.t, r.pos.x(), r.pos.y(), -r.pos.z(), r.euler.x(), r.euler.y(), r.euler.z(), r.air.airspeed,
      r.air.alpha * kDeg, r.air.beta * kDeg, r.ground.head<2>().norm(), r.ground.z(), r.rates.x(),
      r.rates.y(), r.rates.z(), r.controls.brakeLeft, r.controls.brakeRight, r.air.coefficients.CL,
      r.air.coefficients.CD, r.air.coefficients.CY, r.controls.incidence * kDeg, r.requiredGlideDeg, f.x(),
      f.y(), f.z());
}

void writeVtk(const std::filesystem::path& file, const std::vector<FlightRow>& rows) {
  // The path for ParaView: a legacy-VTK polyline in east-north-up coordinates (x east, y north, z altitude;
  // right-handed) with the time, airspeed and descent rate on its points.
  std::ofstream vtk(file);
  vtk << "# vtk DataFile Version 3.0\nfsi fly trajectory (x east, y north, z altitude) [m]\nASCII\n"
      << "DATASET POLYDATA\nPOINTS " << rows.size() << " double\n";
  for (const FlightRow& r : rows)
    vtk << fmt::format("{:.6f} {:.6f} {:.6f}\n", r.pos.y(), r.pos.x(), -r.pos.z());
  vtk << "LINES 1 " << rows.size() + 1 << "\n" << rows.size();
  for (std::size_t i = 0; i < rows.size(); ++i) vtk << " " << i;
  vtk << "\nPOINT_DATA " << rows.size() << "\n";
  auto field = [&](const char* name, auto value) {
    vtk << "SCALARS " << name << " double 1\nLOOKUP_TABLE default\n";
    for (const FlightRow& r : rows) vtk << fmt::format("{:.6g}\n", value(r));
  };
  field("time", [](const FlightRow& r) { return r.t; });
  field("airspeed", [](const FlightRow& r) { return r.air.airspeed; });
  field("descent_rate", [](const FlightRow& r) { return r.ground.z(); });
}

/// summary.md: the summary's numbers as a table a user reads.
void writeSummaryTable(const std::filesystem::path& file, const nlohmann::json& j) {
  std::ofstream md(file);
  md << "# " << j["flight_file"].get<std::string>() << "\n\n| quantity | value |\n|---|---|\n";
  const auto& end = j["end_point_ned_m"];
  md << fmt::format("| landed | {} |\n", j["landed"].get<bool>() ? "yes" : "no (ended in the air)");
  md << fmt::format("| time of flight | {:.1f} s |\n", j["time_of_flight_s"].get<double>());
  md << fmt::format("| end point (north, east, altitude) | {:.1f} m, {:.1f} m, {:.1f} m |\n",
                    end[0].get<double>(), end[1].get<double>(), -end[2].get<double>());
  md << fmt::format("| distance over the ground | {:.1f} m |\n", j["distance_over_ground_m"].get<double>());
  md << fmt::format("| glide ratio, last fifth of the flight | {:.2f} |\n",
                    j["glide_ratio_last_fifth"].get<double>());
  md << fmt::format("| airspeed, descent rate at the end | {:.2f} m/s, {:.2f} m/s |\n",
                    j["airspeed_end_m_s"].get<double>(), j["descent_rate_end_m_s"].get<double>());
  if (j.contains("miss_distance_m"))
    md << fmt::format("| miss distance from the target | {:.1f} m (glide-slope control: {}) |\n",
                      j["miss_distance_m"].get<double>(), j["glide_slope_control"].get<std::string>());
  if (j.contains("monte_carlo")) {
    const auto& m = j["monte_carlo"];
    md << fmt::format("| Monte Carlo | {} runs (seed {}), {} landed |\n", m["runs"].get<int>(),
                      m["seed"].get<std::uint64_t>(), m["landed"].get<int>());
    md << fmt::format(
        "| mean landing point (north, east); standard deviations | {:.1f} m, {:.1f} m; {:.1f} m, {:.1f} m "
        "|\n",
        m["mean_landing_ne_m"][0].get<double>(), m["mean_landing_ne_m"][1].get<double>(),
        m["sd_ne_m"][0].get<double>(), m["sd_ne_m"][1].get<double>());
    md << fmt::format("| miss: mean, median, 95 %, largest | {:.1f}, {:.1f}, {:.1f}, {:.1f} m |\n",
                      m["miss_mean_m"].get<double>(), m["miss_median_m"].get<double>(),
                      m["miss_95_m"].get<double>(), m["miss_max_m"].get<double>());
  }
}

}  // namespace

FlightResult simulateFlight(const FlightCase& c, const std::function<void(const FlightRow&)>& sink) {
  Guidance guidance(c.guidance);
  auto controls = [&](double time, const FlightState& state) {
    return c.guidance.enabled() ? guidance.update(time, state) : c.brakes.at(time);
  };
  FlightRow last;
  int rows = 0;
  auto record = [&](double t, const FlightState& x) {
    FlightRow r;
    r.t = t;
    r.pos = x.position;
    r.euler = eulerDeg(x.attitude);
    r.ground = x.attitude * x.velocity;
    r.rates = x.rates;
    r.controls = controls(t, x);
    r.requiredGlideDeg = guidance.requiredGlideDeg();
    stateRate(c.system, c.wind, r.controls, t, x, &r.air);
    r.aeroForce = x.attitude * r.air.aeroForce;
    ++rows;
    if (sink) sink(r);
    last = r;
  };
  FlightResult res;
  FlightState x = c.initial;
  double t = 0;
  const long steps = long(std::ceil(c.endTime / c.step - 1e-9));
  record(0, x);
  double nextOut = c.outputInterval;
  std::vector<Vec3> outputs{x.position};  // the output points, for the glide over the last fifth
  for (long i = 0; i < steps; ++i) {
    const double dt = std::min(c.step, c.endTime - t);
    const FlightState y = rungeKuttaStep(c.system, c.wind, controls(t, x), t, dt, x);
    if (!finite(y))
      throw std::runtime_error(
          fmt::format("{}: the flight state stopped being finite at t = {:.6g} s (last finite: altitude "
                      "{:.6g} m, speed {:.6g} "
                      "m/s, rates {:.3g} rad/s); a smaller time.step, or check the inertia and apparent mass",
                      c.file, t + dt, -x.position.z(), x.velocity.norm(), x.rates.norm()));
    if (c.stopAtGround && y.position.z() >= 0) {  // crossed the ground: interpolate the landing point
      const double s = -x.position.z() / (y.position.z() - x.position.z());
      res.landed = true;
      res.time = t + s * dt;
      res.landing = x.position + s * (y.position - x.position);
      x = y;
      t += dt;
      record(res.time, y);
      outputs.push_back(y.position);
      break;
    }
    x = y;
    t += dt;
    if (t >= nextOut - 1e-9 || i + 1 == steps) {
      record(t, x);
      outputs.push_back(x.position);
      nextOut += c.outputInterval;
    }
  }
  if (!res.landed) {
    res.time = t;
    res.landing = x.position;
  }
  res.airspeed = last.air.airspeed;
  res.descentRate = last.ground.z();
  const Vec3 d = outputs.back() - outputs[outputs.size() * 4 / 5];
  res.glideRatio = d.z() > 0 ? d.head<2>().norm() / d.z() : 0.0;
  res.rows = rows;
  res.waypoint = guidance.waypoint();
  return res;
}

FlightResult runFlight(const FlightCase& c, const std::filesystem::path& outDir, bool quiet) {
  std::error_code ec;
  std::filesystem::create_directories(outDir, ec);
  if (ec) throw InputError(fmt::format("{}: cannot create the folder: {}", outDir.string(), ec.message()));
  const std::filesystem::path csvPath = outDir / "trajectory.csv";
  std::ofstream csv(csvPath);
  if (!csv) throw InputError(fmt::format("{}: cannot write", csvPath.string()));
  csv << "time_s,north_m,east_m,altitude_m,roll_deg,pitch_deg,yaw_deg,airspeed_m_s,alpha_deg,beta_deg,"
         "ground_speed_m_s,descent_rate_m_s,p_rad_s,q_rad_s,r_rad_s,brake_left,brake_right,CL,CD,CY,"
         "incidence_deg,required_glide_deg,aero_force_north_N,aero_force_east_N,aero_force_down_N\n";
  std::vector<FlightRow> rows;
  const FlightResult res = simulateFlight(c, [&](const FlightRow& r) {
    rows.push_back(r);
    writeCsvRow(csv, r);
    if (!quiet && rows.size() % 100 == 0)
      fmt::print("[fsi fly] t = {:.1f} s  altitude {:.1f} m  airspeed {:.2f} m/s\n", r.t, -r.pos.z(),
                 r.air.airspeed);
  });
  writeVtk(outDir / "trajectory.vtk", rows);
  nlohmann::json j;
  j["flight_file"] = c.file;
  j["landed"] = res.landed;
  j["time_of_flight_s"] = res.time;
  j["end_point_ned_m"] = {res.landing.x(), res.landing.y(), res.landing.z()};
  j["start_point_ned_m"] = {c.initial.position.x(), c.initial.position.y(), c.initial.position.z()};
  j["distance_over_ground_m"] = (res.landing - c.initial.position).head<2>().norm();
  j["glide_ratio_last_fifth"] = res.glideRatio;
  j["airspeed_end_m_s"] = res.airspeed;
  j["descent_rate_end_m_s"] = res.descentRate;
  j["trajectory_rows"] = res.rows;
  j["step_s"] = c.step;
  if (c.guidance.enabled()) {
    const auto& target = c.guidance.waypoints.back();
    j["waypoints_ne_m"] = c.guidance.waypoints;
    j["target_ne_m"] = target;
    j["miss_distance_m"] = std::hypot(res.landing.x() - target[0], res.landing.y() - target[1]);
    j["waypoint_reached"] = res.waypoint;
    j["glide_slope_control"] = c.guidance.glideSlope.enabled() ? c.guidance.glideSlope.control : "none";
  }
  j["wind_steady_ned_m_s"] = {c.wind.steady.x(), c.wind.steady.y(), c.wind.steady.z()};
  j["integrator"] = "classical Runge-Kutta, 4th order";
  if (c.monteCarlo.enabled()) {
    const MonteCarloResult m = runMonteCarlo(c, outDir);
    j["monte_carlo"] = {{"runs", m.runs},
                        {"seed", c.monteCarlo.seed},
                        {"landed", m.landed},
                        {"mean_landing_ne_m", {m.meanNorth, m.meanEast}},
                        {"sd_ne_m", {m.sdNorth, m.sdEast}},
                        {"miss_mean_m", m.missMean},
                        {"miss_median_m", m.missMedian},
                        {"miss_95_m", m.miss95},
                        {"miss_max_m", m.missMax},
                        {"file", "monte_carlo.csv"}};
  }
  std::ofstream(outDir / "summary.json") << j.dump(1) << "\n";
  writeSummaryTable(outDir / "summary.md", j);
  return res;
}

}  // namespace fsi::flight
