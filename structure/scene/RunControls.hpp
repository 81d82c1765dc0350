#pragma once
// The run settings a scene gives its solver: time control, the integrator choice and the output. Plain
// data, read from the scene's `time:`, `solver:` and `output:` sections (ReadControls.cpp).

#include <limits>
#include <set>
#include <string>
#include <vector>

#include "structure/elements/ElementKind.hpp"
#include "structure/integrate/CentralDifference.hpp"
#include "structure/integrate/DynamicRelaxation.hpp"

namespace fsi::structure {

struct TimeControl {
  double endTime = 0;  ///< simulated end time (or the cap for until-static runs)
  bool untilStatic = false;
  double staticTolerance = 1e-8;  ///< stop when KE/strain energy stays below this
  long monitorEvery = 100;        ///< steps between energy checks
  double energyTolerance = 0.05;  ///< relative energy-balance error that counts as instability
  double massScalingMinDt = 0;    ///< > 0: selective mass scaling to this step
  CentralDifferenceSettings integrator;
};

/// Which integrator a scene runs: explicit dynamics (default) or dynamic relaxation to a static state.
struct SolverControl {
  enum class Type { ExplicitDynamics, DynamicRelaxation };
  Type type = Type::ExplicitDynamics;
  RelaxationSettings relaxation;
  std::string method;  ///< label of the DR variant (KDR, KDR1, oDR, mdDR, ...)
  int threads = 1;     ///< solver.threads: threads for the force kernels and node sweeps
};

struct OutputControl {
  double interval = 0;  ///< simulated time between frames; 0 = first and last only
  std::set<std::string> fields;
};

/// The valid `output.fields`: the node fields, then every element kind's own (ElementKind::outputFields, in
/// registry order).
inline const std::vector<std::string>& allOutputFields() {
  static const std::vector<std::string> f = [] {
    std::vector<std::string> all{"displacement", "velocity", "residual"};
    for (const ElementKind* kind : elementKinds())
      for (const std::string& name : kind->outputFields()) all.push_back(name);
    return all;
  }();
  return f;
}

}  // namespace fsi::structure
