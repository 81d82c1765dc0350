// stress: the maximum or minimum principal membrane stress of a set of triangles, reduced over them.
#include "structure/probes/ProbeKinds.hpp"

namespace fsi::structure {

namespace {

const std::vector<std::string> kKeys{"type", "triangles", "quantity", "reduce"};

void parse(const YamlMap& p, const SetResolver& sets, ProbeSpec& spec) {
  spec.triangles = sets.triangles(p.required("triangles"), p.childPath("triangles"));
  spec.quantity = p.choice("quantity", {"max_principal", "min_principal"}, "max_principal") == "min_principal"
                      ? StressQuantity::MinPrincipal
                      : StressQuantity::MaxPrincipal;
  spec.reduce = readReduce(p, {"max", "min", "mean"}, "max");
  p.finish(kKeys);
}

void evaluate(const ProbeSpec& p, ProbeState& state, std::vector<double>& vals) {
  const MembraneStressField& stress = state.membraneStress();
  // principal holds (max, min) per element.
  const int which = p.quantity == StressQuantity::MinPrincipal ? 1 : 0;
  for (int e : p.triangles) vals.push_back(stress.principal[2 * e + which]);
}

}  // namespace

ProbeKind stressProbe() {
  return {"stress", kKeys, "the max or min principal membrane stress over a set of triangles", parse,
          evaluate};
}

}  // namespace fsi::structure
