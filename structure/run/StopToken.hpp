#pragma once
// A request to stop a run cleanly, handed to the run in RunOptions::stop. Runs poll it at every step or
// relaxation iteration and during their set-up, and stop with the state saved (interrupted_state.h5, exit
// code 130, or 128 + the signal that made the request: 143 for SIGTERM). Runs never clear it: a request made
// before a run starts (a Ctrl-C while the scene loads) stops that run as soon as it begins, and one token
// shared by several runs (`fsi validate`) stops all that remain.
// Setting it is async-signal-safe, so a SIGINT/SIGTERM handler may do it (Interrupt.hpp), as may another
// thread.

#include <atomic>

namespace fsi::structure {

class StopToken {
 public:
  /// Requests a stop; `signal` is the signal that asked for it (0: none, a request from code). The first
  /// request's signal is kept.
  void request(int signal = 0) noexcept {
    int none = 0;
    if (signal != 0) signal_.compare_exchange_strong(none, signal, std::memory_order_relaxed);
    flag_.store(true, std::memory_order_relaxed);
  }
  bool requested() const noexcept { return flag_.load(std::memory_order_relaxed); }
  /// The signal of the first request that came from one (SIGINT, SIGTERM), 0 if none did.
  int signal() const noexcept { return signal_.load(std::memory_order_relaxed); }
  /// Forgets a request (for programs that go on after a stopped run, and for tests). Runs never call it.
  void clear() noexcept {
    flag_.store(false, std::memory_order_relaxed);
    signal_.store(0, std::memory_order_relaxed);
  }

 private:
  static_assert(std::atomic<bool>::is_always_lock_free,
                "a lock-free flag is safe to set in a signal handler");
  static_assert(std::atomic<int>::is_always_lock_free, "a lock-free int is safe to set in a signal handler");
  std::atomic<bool> flag_{false};
  std::atomic<int> signal_{0};
};

}  // namespace fsi::structure
