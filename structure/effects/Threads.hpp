#pragma once
// Threads for the structure solver's hot loops (scene key solver.threads; docs/PERFORMANCE.md "Threads").
//
// The thread count travels with the integrators' settings into their ThreadedForces; nothing reads
// OMP_NUM_THREADS, so a scene without the key runs on one thread whatever the
// environment says. Evaluations whose largest split effect (ThreadedForces.hpp) has fewer than
// kMinParallelItems elements stay serial: waking the threads costs more than they would save.

namespace fsi::structure {

/// Whether this build has OpenMP (FSI_OPENMP and a compiler that supports it). Without it a thread count
/// above 1 is an input error.
bool threadsAvailable();

/// Elements below which a force evaluation (and the node sweep with it) runs serially whatever the thread
/// count. The measured crossover of a whole step, 1 against 2 threads (docs/PERFORMANCE.md "Threads"): a
/// threaded step costs a fixed ≈ 55–70 µs more with OMP_WAIT_POLICY=passive (fork, barrier and join each
/// wake a sleeping thread on this kind of virtual machine) and saves ≈ 8.5 ns per triangle, so 2 threads
/// break even at about 6 500–8 000 triangles. One constant for every split effect: they run in one region.
constexpr int kMinParallelItems = 8000;

/// While alive, every parallel region runs on one thread (OpenMP's max-active-levels set to 0), which then
/// takes all the shares one after the other, as when the runtime gives fewer threads than asked. Tests use
/// it to check that a threaded result does not depend on the scheduling. Does nothing without OpenMP.
class OneThreadScope {
 public:
  OneThreadScope();
  ~OneThreadScope();
  OneThreadScope(const OneThreadScope&) = delete;
  OneThreadScope& operator=(const OneThreadScope&) = delete;

 private:
  int saved_ = 0;
};

}  // namespace fsi::structure
