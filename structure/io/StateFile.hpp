#pragma once
// StateFile: checkpoint / last-good-state / restart snapshots of the structure in one HDF5 file.
//
// Layout: root attributes fsi_state_version (=1), time, step, dt; datasets /x and /v (3N, xyz interleaved);
// /scalars/<name> (scalar datasets) and /arrays/<name> (1-D datasets).

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace fsi::structure {

struct StateSnapshot {
  double time = 0;
  long step = 0;
  double dt = 0;
  std::vector<double> x, v;                           ///< positions and velocities, 3N each, xyz interleaved
  std::map<std::string, double> scalars;              ///< energies etc.
  std::map<std::string, std::vector<double>> arrays;  ///< any further per-entity state
};

/// Writes atomically (temporary file next to `file`, synced, then renamed), so `file` always holds either the
/// previous or the new complete snapshot. Throws std::invalid_argument for inconsistent sizes or names that
/// HDF5 cannot store ('/' or empty), std::runtime_error naming the file on I/O failure.
void writeState(const std::filesystem::path& file, const StateSnapshot& state);

/// Throws fsi::InputError naming the file if it is missing, not HDF5, or not a complete state file.
StateSnapshot readState(const std::filesystem::path& file);

}  // namespace fsi::structure
