#pragma once
// Threads for the structure solver's hot loops (scene key solver.threads; docs/PERFORMANCE.md "Threads").
//
// The thread count travels with each force evaluation (ForceContext::threads) and with the integrator's
// settings; nothing reads OMP_NUM_THREADS, so a scene without the key runs on one thread whatever the
// environment says. Loops below kMinParallelItems items stay serial: starting the threads costs more
// than they would save.

namespace fsi::structure {

/// Whether this build has OpenMP (FSI_OPENMP and a compiler that supports it). Without it a thread count
/// above 1 is an input error.
bool threadsAvailable();

/// Elements (or nodes) below which a loop runs serially whatever the thread count.
constexpr int kMinParallelItems = 2000;

}  // namespace fsi::structure
