#pragma once
// FlightRun: integrates a FlightCase and writes what a user looks at: trajectory.csv (one row per output
// interval: time, position, attitude, air data, brakes), summary.json (the flight in numbers: landing point,
// time of flight, the glide over the last part, the extremes) and the exit status. A state that stops being
// finite ends the run with a diagnosis naming the time and the last finite state.

#include <filesystem>
#include <functional>
#include <string>

#include "flight/FlightFile.hpp"

namespace fsi::flight {

struct FlightResult {
  bool landed = false;
  double time = 0;                       ///< end of the flight [s]
  Vec3 landing = Vec3::Zero();           ///< NED at the end (the ground crossing interpolated when landed)
  double glideRatio = 0;                 ///< horizontal over vertical distance of the last 20 % of the flight
  double airspeed = 0, descentRate = 0;  ///< at the end [m/s]
  int rows = 0;                          ///< trajectory rows written
  int waypoint = 0;                      ///< the guidance's waypoint at the end (index)
};

/// One output row of a flight: what trajectory.csv holds.
struct FlightRow {
  double t = 0;
  Vec3 pos = Vec3::Zero(), euler = Vec3::Zero(), ground = Vec3::Zero();  ///< NED; roll, pitch, yaw [deg]
  Vec3 rates = Vec3::Zero();
  Vec3 aeroForce = Vec3::Zero();  ///< canopy, lines and payload, world axes (NED) [N]
  FlightReading air;
  Controls controls;
  double requiredGlideDeg = 0;  ///< the glide-slope loop's glide path (0 without it)
};

/// Integrates the flight, calling `sink` (if any) with a row per output interval and at the end; no files.
/// Throws std::runtime_error for a state that is no longer finite.
FlightResult simulateFlight(const FlightCase& c, const std::function<void(const FlightRow&)>& sink = {});

/// Runs the flight and writes outDir/trajectory.csv and outDir/summary.json. Throws fsi::InputError for an
/// unwritable folder and std::runtime_error for a state that is no longer finite.
FlightResult runFlight(const FlightCase& c, const std::filesystem::path& outDir, bool quiet = false);

}  // namespace fsi::flight
