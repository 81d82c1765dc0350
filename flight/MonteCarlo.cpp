#include "flight/MonteCarlo.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <vector>

#include "flight/FlightFile.hpp"
#include "flight/FlightRun.hpp"
#include "structure/model/Error.hpp"

namespace fsi::flight {

namespace {

/// Uniform in [0, 1) from the 53 high bits of the engine's output (the same on every platform, unlike
/// std::uniform_real_distribution, whose algorithm the standard leaves open).
double uniform(std::mt19937_64& g) {
  return double(g() >> 11) * 0x1.0p-53;
}

/// A standard normal number (Box–Muller, the cosine branch).
double normal(std::mt19937_64& g) {
  const double u1 = 1.0 - uniform(g), u2 = uniform(g);  // u1 in (0, 1]
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2 * M_PI * u2);
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const double pos = q * double(v.size() - 1);
  const std::size_t i = std::size_t(pos);
  return i + 1 < v.size() ? v[i] + (pos - double(i)) * (v[i + 1] - v[i]) : v.back();
}

}  // namespace

MonteCarloResult runMonteCarlo(const FlightCase& c, const std::filesystem::path& outDir) {
  const MonteCarloParams& p = c.monteCarlo;
  std::mt19937_64 g(p.seed);
  std::ofstream csv(outDir / "monte_carlo.csv");
  if (!csv) throw InputError(fmt::format("{}: cannot write", (outDir / "monte_carlo.csv").string()));
  csv << "run,release_north_m,release_east_m,release_altitude_m,wind_speed_m_s,wind_from_deg,wind_north_m_s,"
         "wind_east_m_s,landed,time_s,landing_north_m,landing_east_m,miss_m\n";
  MonteCarloResult r;
  std::vector<double> north, east, miss;
  for (int i = 0; i < p.runs; ++i) {
    // Draw in a fixed order: wind speed, wind direction, release north, east, altitude.
    const double speed = p.windSpeed[0] + (p.windSpeed[1] - p.windSpeed[0]) * uniform(g);
    const double from = p.windFrom[0] + (p.windFrom[1] - p.windFrom[0]) * uniform(g);
    const Vec3 offset(p.releaseSd[0] * normal(g), p.releaseSd[1] * normal(g), -p.releaseSd[2] * normal(g));
    FlightCase run = c;
    const double a = from * M_PI / 180.0;
    const Vec3 wind(-speed * std::cos(a), -speed * std::sin(a), 0);  // blows away from where it comes from
    run.wind.steady += wind;
    run.initial.position += offset;
    run.initial.position.z() = std::min(run.initial.position.z(), 0.0);  // not below the ground
    const FlightResult f = simulateFlight(run);
    double m = 0;
    if (c.guidance.enabled()) {
      const auto& target = c.guidance.waypoints.back();
      m = std::hypot(f.landing.x() - target[0], f.landing.y() - target[1]);
    }
    csv << fmt::format("{},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{},{:.6f},{:.6f},{:.6f},{:.6f}\n",
                       i, run.initial.position.x(), run.initial.position.y(), -run.initial.position.z(),
                       speed, from, wind.x(), wind.y(), f.landed ? 1 : 0, f.time, f.landing.x(),
                       f.landing.y(), m);
    r.landed += f.landed ? 1 : 0;
    north.push_back(f.landing.x());
    east.push_back(f.landing.y());
    miss.push_back(m);
  }
  r.runs = p.runs;
  const double n = double(p.runs);
  for (int i = 0; i < p.runs; ++i) {
    r.meanNorth += north[i] / n;
    r.meanEast += east[i] / n;
    r.missMean += miss[i] / n;
  }
  if (p.runs > 1) {
    for (int i = 0; i < p.runs; ++i) {
      r.sdNorth += (north[i] - r.meanNorth) * (north[i] - r.meanNorth);
      r.sdEast += (east[i] - r.meanEast) * (east[i] - r.meanEast);
    }
    r.sdNorth = std::sqrt(r.sdNorth / (n - 1));
    r.sdEast = std::sqrt(r.sdEast / (n - 1));
  }
  r.missMedian = quantile(miss, 0.5);
  r.miss95 = quantile(miss, 0.95);
  r.missMax = miss.empty() ? 0 : *std::max_element(miss.begin(), miss.end());
  return r;
}

}  // namespace fsi::flight
