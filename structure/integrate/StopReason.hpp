#pragma once
// Why a run (explicit or dynamic relaxation) stopped: the one encoding every solver, the summary
// (summary.json `stop_reason`), the exit code and the stop handling use.

#include <string>

namespace fsi::structure {

enum class StopReason {
  EndTime,       ///< the end time was reached
  Static,        ///< the static state was reached (until_static, or a converged relaxation)
  NotConverged,  ///< the time or iteration limit came first
  Unstable,      ///< instability, non-finite state or divergence
  Interrupted,   ///< a stop request (StopToken)
};

/// The name in summary.json: end_time, static, not_converged, unstable, interrupted.
std::string toString(StopReason r);

/// The exit code of `fsi run`: 0 for a normal end, 3 unstable, 4 not converged; interrupted: 128 + the signal
/// that asked for the stop (130 SIGINT, 143 SIGTERM), 130 when no signal did (`signal` 0).
int exitCode(StopReason r, int signal = 0);

}  // namespace fsi::structure
