#pragma once
// MonteCarlo: the landing point's dispersion over random winds and release points. From a seed, every run
// draws a steady wind (speed and the direction it blows from, uniform in the given ranges, added to the
// flight file's wind) and a release point (the file's start moved by normal offsets of the given standard
// deviations in north, east and altitude) and flies the case to the ground without writing its path. The
// random numbers come from std::mt19937_64 (its sequence is fixed by the C++ standard) through the project's
// own uniform and Box–Muller transforms, so a seed gives the same runs on every platform and compiler.
// Writes monte_carlo.csv (one row per run) and returns the statistics for summary.json.

#include <array>
#include <cstdint>
#include <filesystem>

namespace fsi::flight {

struct FlightCase;

struct MonteCarloParams {
  int runs = 0;  ///< 0: no Monte Carlo
  std::uint64_t seed = 1;
  std::array<double, 2> windSpeed{0, 0};     ///< [m/s], uniform between
  std::array<double, 2> windFrom{0, 360};    ///< [deg from north, where the wind comes from], uniform between
  std::array<double, 3> releaseSd{0, 0, 0};  ///< north, east, altitude [m], normal
  bool enabled() const { return runs > 0; }
};

struct MonteCarloResult {
  int runs = 0, landed = 0;
  double meanNorth = 0, meanEast = 0;                            ///< mean landing point [m]
  double sdNorth = 0, sdEast = 0;                                ///< sample standard deviations [m]
  double missMean = 0, missMedian = 0, miss95 = 0, missMax = 0;  ///< distance to the target [m] (guidance)
};

/// Runs c.monteCarlo and writes outDir/monte_carlo.csv. Throws std::runtime_error when a run fails.
MonteCarloResult runMonteCarlo(const FlightCase& c, const std::filesystem::path& outDir);

}  // namespace fsi::flight
