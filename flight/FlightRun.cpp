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

struct Row {
  double t;
  Vec3 pos, euler, ground;
  FlightReading air;
  Controls brakes;
};

}  // namespace

FlightResult runFlight(const FlightCase& c, const std::filesystem::path& outDir, bool quiet) {
  std::error_code ec;
  std::filesystem::create_directories(outDir, ec);
  if (ec) throw InputError(fmt::format("{}: cannot create the folder: {}", outDir.string(), ec.message()));
  const std::filesystem::path csvPath = outDir / "trajectory.csv";
  std::ofstream csv(csvPath);
  if (!csv) throw InputError(fmt::format("{}: cannot write", csvPath.string()));
  csv << "time_s,north_m,east_m,altitude_m,roll_deg,pitch_deg,yaw_deg,airspeed_m_s,alpha_deg,beta_deg,"
         "ground_speed_m_s,descent_rate_m_s,p_rad_s,q_rad_s,r_rad_s,brake_left,brake_right,CL,CD\n";
  std::vector<Row> rows;
  Guidance guidance(c.guidance);
  auto controls = [&](double time, const FlightState& state) {
    return c.guidance.enabled() ? guidance.update(time, state) : c.brakes.at(time);
  };
  auto record = [&](double t, const FlightState& x) {
    Row r{t, x.position, eulerDeg(x.attitude), x.attitude * x.velocity, {}, controls(t, x)};
    stateRate(c.system, c.wind, r.brakes, t, x, &r.air);
    rows.push_back(r);
    csv << fmt::format(
        "{:.6f},{:.6f},{:.6f},{:.6f},{:.5f},{:.5f},{:.5f},{:.6f},{:.5f},{:.5f},{:.6f},{:.6f},{:.6f},{:.6f},"
        "{:.6f},{:.4f},{:.4f},{:.6f},{:.6f}\n",
        t, x.position.x(), x.position.y(), -x.position.z(), r.euler.x(), r.euler.y(), r.euler.z(),
        r.air.airspeed, r.air.alpha * kDeg, r.air.beta * kDeg, r.ground.head<2>().norm(), r.ground.z(),
        x.rates.x(), x.rates.y(), x.rates.z(), r.brakes.brakeLeft, r.brakes.brakeRight, r.air.coefficients.CL,
        r.air.coefficients.CD);
  };
  FlightResult res;
  FlightState x = c.initial;
  double t = 0, nextOut = 0;
  const long steps = long(std::ceil(c.endTime / c.step - 1e-9));
  record(0, x);
  nextOut = c.outputInterval;
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
      break;
    }
    x = y;
    t += dt;
    if (t >= nextOut - 1e-9 || i + 1 == steps) {
      record(t, x);
      nextOut += c.outputInterval;
      if (!quiet && rows.size() % 100 == 0)
        fmt::print("[fsi fly] t = {:.1f} s  altitude {:.1f} m  airspeed {:.2f} m/s\n", t, -x.position.z(),
                   rows.back().air.airspeed);
    }
  }
  if (!res.landed) {
    res.time = t;
    res.landing = x.position;
  }
  const Row& last = rows.back();
  res.airspeed = last.air.airspeed;
  res.descentRate = last.ground.z();
  const std::size_t from = rows.size() * 4 / 5;
  const Vec3 d = rows.back().pos - rows[from].pos;
  res.glideRatio = d.z() > 0 ? d.head<2>().norm() / d.z() : 0.0;
  res.rows = int(rows.size());
  // The path for ParaView: a legacy-VTK polyline in east-north-up coordinates (x east, y north, z altitude;
  // right-handed) with the time, airspeed and descent rate on its points.
  {
    std::ofstream vtk(outDir / "trajectory.vtk");
    vtk << "# vtk DataFile Version 3.0\nfsi fly trajectory (x east, y north, z altitude) [m]\nASCII\n"
        << "DATASET POLYDATA\nPOINTS " << rows.size() << " double\n";
    for (const Row& r : rows) vtk << fmt::format("{:.6f} {:.6f} {:.6f}\n", r.pos.y(), r.pos.x(), -r.pos.z());
    vtk << "LINES 1 " << rows.size() + 1 << "\n" << rows.size();
    for (std::size_t i = 0; i < rows.size(); ++i) vtk << " " << i;
    vtk << "\nPOINT_DATA " << rows.size() << "\n";
    auto field = [&](const char* name, auto value) {
      vtk << "SCALARS " << name << " double 1\nLOOKUP_TABLE default\n";
      for (const Row& r : rows) vtk << fmt::format("{:.6g}\n", value(r));
    };
    field("time", [](const Row& r) { return r.t; });
    field("airspeed", [](const Row& r) { return r.air.airspeed; });
    field("descent_rate", [](const Row& r) { return r.ground.z(); });
  }
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
    j["waypoint_reached"] = guidance.waypoint();
  }
  j["wind_steady_ned_m_s"] = {c.wind.steady.x(), c.wind.steady.y(), c.wind.steady.z()};
  j["integrator"] = "classical Runge-Kutta, 4th order";
  std::ofstream(outDir / "summary.json") << j.dump(1) << "\n";
  return res;
}

}  // namespace fsi::flight
