#pragma once
// FlightFile: a flight described in YAML (FLIGHT.yaml, docs/FLIGHT.md "The flight file"): the system, its
// aerodynamic table, the wind, the start, the brake inputs and the time control. Read strictly like a scene:
// every key located (file:line:col), unknown keys refused with a "did you mean", --set overrides.

#include <filesystem>
#include <string>
#include <vector>

#include "flight/FlightSystem.hpp"
#include "flight/Guidance.hpp"
#include "flight/MonteCarlo.hpp"

namespace fsi::flight {

/// Brake inputs as a piecewise-linear table of time [s] against left and right brake (0 … 1) and, optionally,
/// the incidence (the rigging's change, radians; docs/FLIGHT.md).
struct BrakeSchedule {
  std::vector<double> time, left, right;  ///< empty: no brake
  std::vector<double> incidence;          ///< empty or one per time [rad]
  Controls at(double t) const;
};

struct FlightCase {
  std::string file;  ///< where it was read from (messages, summary)
  FlightSystem system;
  Wind wind;
  FlightState initial;
  BrakeSchedule brakes;
  GuidanceParams guidance;      ///< waypoints given: the autopilot flies the brakes (no `brakes` table then)
  MonteCarloParams monteCarlo;  ///< runs > 0: the landing dispersion over random winds and release points
  double endTime = 600;         ///< [s]
  double step = 0.01;           ///< RK4 step [s]
  double outputInterval = 0.1;  ///< [s]
  bool stopAtGround = true;     ///< end at altitude 0 (the landing point interpolated)
};

/// Reads a flight file; `overrides` are --set key.path=value assignments. Throws fsi::InputError located at
/// the file, line and key for anything unusable.
FlightCase readFlightFile(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});
FlightCase readFlightString(const std::string& yaml, const std::string& name,
                            const std::vector<std::string>& overrides = {});

}  // namespace fsi::flight
