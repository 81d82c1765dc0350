#pragma once
// Ctrl-C (SIGINT) as a request to stop cleanly. The handler only sets a flag; runs poll it at every step or
// iteration and during their set-up, and stop with the state saved (interrupted_state.h5, exit code 130).
// A request is never cleared by a run: one that arrives before a run starts (while the scene loads) stops
// that run as soon as it begins, and in `fsi validate` it stops every remaining run.

namespace fsi::structure {

/// Installs the SIGINT handler. Call it first thing in a program that runs simulations, so that no Ctrl-C
/// between start-up and the first step is lost or kills the process.
void installInterruptHandler();

/// True once SIGINT arrived (or requestInterrupt() was called) and the request was not cleared.
bool interruptRequested();

/// What the handler does: asks running simulations to stop (tests and embedding programs use it).
void requestInterrupt();

/// Forgets a request (for programs that go on after an interrupted run, and for tests). Runs never call it.
void clearInterruptRequest();

}  // namespace fsi::structure
