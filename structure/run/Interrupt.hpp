#pragma once
// Ctrl-C (SIGINT) and SIGTERM (kill, a batch system's time limit, systemd) as requests to stop cleanly: the
// handler only requests the program's StopToken, with the signal's number, which the program passes to its
// runs (RunOptions::stop). A run stopped so exits with 128 + the signal (130 SIGINT, 143 SIGTERM) after
// writing its state and summary.

#include "structure/run/StopToken.hpp"

namespace fsi::structure {

/// Installs the SIGINT and SIGTERM handlers that request `token`; `token` must live as long as the handlers
/// can fire (a static object of the program). Call it first thing in a program that runs simulations, so that
/// no signal between start-up and the first step is lost or kills the process.
void installInterruptHandler(StopToken& token);

/// For a program (or command) with no run to stop: SIGINT and SIGTERM get their default action again, and a
/// signal the handler already caught is raised again, so that it ends the process as it would have.
void restoreDefaultInterrupts();

}  // namespace fsi::structure
