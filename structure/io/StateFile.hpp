#pragma once
// StateFile: a StateSnapshot (last good state, interrupted state, restart) in one HDF5 file.
//
// Layout: root attributes fsi_state_version (=1), time, step, dt; datasets /x and /v (3N, xyz interleaved);
// /scalars/<name> (scalar datasets) and /arrays/<name> (1-D datasets). Not stored: the snapshot's ledger and
// stableDt (a writer that needs the ledger puts it in `arrays`).

#include <filesystem>

#include "structure/integrate/StateSnapshot.hpp"

namespace fsi::structure {

/// Writes atomically (temporary file next to `file`, synced, then renamed), so `file` always holds either the
/// previous or the new complete snapshot. Throws std::invalid_argument for inconsistent sizes or names that
/// HDF5 cannot store ('/' or empty), std::runtime_error naming the file on I/O failure.
void writeState(const std::filesystem::path& file, const StateSnapshot& state);

/// Throws fsi::InputError naming the file if it is missing, not HDF5, or not a complete state file (every
/// attribute a scalar of its type, every dataset of its rank).
StateSnapshot readState(const std::filesystem::path& file);

/// True if `file` is an HDF5 file tagged as a state file (root attribute fsi_state_version), whatever else
/// it holds; false for anything else (missing, not HDF5, a results file). Never throws.
bool isStateFile(const std::filesystem::path& file);

}  // namespace fsi::structure
