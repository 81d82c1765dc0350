#include "structure/integrate/StopReason.hpp"

namespace fsi::structure {

std::string toString(StopReason r) {
  switch (r) {
    case StopReason::EndTime:
      return "end_time";
    case StopReason::Static:
      return "static";
    case StopReason::NotConverged:
      return "not_converged";
    case StopReason::Unstable:
      return "unstable";
    case StopReason::Interrupted:
      return "interrupted";
  }
  return "?";
}

int exitCode(StopReason r, int signal) {
  switch (r) {
    case StopReason::Unstable:
      return 3;
    case StopReason::Interrupted:
      return signal > 0 && signal < 128 ? 128 + signal : 130;
    case StopReason::NotConverged:
      return 4;
    default:
      return 0;
  }
}

}  // namespace fsi::structure
