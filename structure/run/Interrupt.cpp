#include "structure/run/Interrupt.hpp"

#include <csignal>

namespace fsi::structure {

namespace {
volatile std::sig_atomic_t gInterrupted = 0;
extern "C" void onInterrupt(int) {
  gInterrupted = 1;
}
}  // namespace

void installInterruptHandler() {
  // sigaction rather than signal(): the handler stays installed after the first signal (no reset to the
  // default action, which a second Ctrl-C during the state write would turn into a kill), and interrupted
  // system calls restart instead of failing the file I/O in progress.
  struct sigaction sa {};
  sa.sa_handler = onInterrupt;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  sigaction(SIGINT, &sa, nullptr);
}

bool interruptRequested() {
  return gInterrupted != 0;
}

void requestInterrupt() {
  gInterrupted = 1;
}

void clearInterruptRequest() {
  gInterrupted = 0;
}

}  // namespace fsi::structure
