// evaluateProbes (declared in run/Simulation.hpp): every probe of the scene at the current state.
#include <algorithm>

#include "structure/probes/ProbeKinds.hpp"
#include "structure/run/Simulation.hpp"

namespace fsi::structure {

namespace {

double reduceValues(const std::vector<double>& vals, ProbeReduce r) {
  switch (r) {
    case ProbeReduce::Value:
      return vals.front();
    case ProbeReduce::Mean: {
      double s = 0;
      for (double v : vals) s += v;
      return s / double(vals.size());
    }
    case ProbeReduce::Max:
      return *std::max_element(vals.begin(), vals.end());
    case ProbeReduce::Min:
      return *std::min_element(vals.begin(), vals.end());
    case ProbeReduce::Sum: {
      double s = 0;
      for (double v : vals) s += v;
      return s;
    }
  }
  return 0.0;
}

}  // namespace

std::map<std::string, double> evaluateProbes(const Scene& scene) {
  std::map<std::string, double> out;
  ProbeState state(*scene.model, scene.constraints);
  std::vector<double> vals;
  for (const ProbeSpec& p : scene.probes) {
    vals.clear();
    p.kind->evaluate(p, state, vals);
    out[p.name] = reduceValues(vals, p.reduce);
  }
  return out;
}

}  // namespace fsi::structure
