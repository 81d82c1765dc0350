#include "structure/run/Interrupt.hpp"

#include <csignal>

namespace fsi::structure {

namespace {
// The token the signal requests: a signal handler reaches nothing but static storage. Lock-free, so reading
// it in the handler is safe.
std::atomic<StopToken*> gSigintToken{nullptr};
static_assert(std::atomic<StopToken*>::is_always_lock_free, "read in a signal handler");

extern "C" void onInterrupt(int signal) {
  if (StopToken* token = gSigintToken.load(std::memory_order_relaxed)) token->request(signal);
}

constexpr int kSignals[] = {SIGINT, SIGTERM};
}  // namespace

void installInterruptHandler(StopToken& token) {
  gSigintToken.store(&token);
  // sigaction rather than signal(): the handler stays installed after the first signal (no reset to the
  // default action, which a second Ctrl-C during the state write would turn into a kill), and interrupted
  // system calls restart instead of failing the file I/O in progress.
  struct sigaction sa {};
  sa.sa_handler = onInterrupt;
  sigemptyset(&sa.sa_mask);
  for (const int s : kSignals) sigaddset(&sa.sa_mask, s);  // one handler at a time
  sa.sa_flags = SA_RESTART;
  for (const int s : kSignals) sigaction(s, &sa, nullptr);
}

void restoreDefaultInterrupts() {
  for (const int s : kSignals) std::signal(s, SIG_DFL);
  const StopToken* token = gSigintToken.load();
  if (token != nullptr && token->signal() != 0) std::raise(token->signal());
}

}  // namespace fsi::structure
