#pragma once
// Ctrl-C (SIGINT) as a request to stop cleanly: the handler only requests the program's StopToken, which the
// program passes to its runs (RunOptions::stop).

#include "structure/run/StopToken.hpp"

namespace fsi::structure {

/// Installs the SIGINT handler that requests `token`; `token` must live as long as the handler can fire (a
/// static object of the program). Call it first thing in a program that runs simulations, so that no Ctrl-C
/// between start-up and the first step is lost or kills the process.
void installInterruptHandler(StopToken& token);

}  // namespace fsi::structure
