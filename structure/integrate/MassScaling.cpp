#include "structure/integrate/MassScaling.hpp"

#include <algorithm>
#include <limits>

#include "structure/elements/ElementKind.hpp"

namespace fsi::structure {

double referenceStableDt(const Model& model) {
  double dt = std::numeric_limits<double>::infinity();
  for (const ElementKind* kind : elementKinds()) dt = std::min(dt, kind->referenceStableDt(model));
  return dt;
}

MassScalingReport applyMassScaling(Model& model, double targetDt, double safety) {
  MassScalingReport r;
  Nodes& N = model.nodes;
  for (double m : N.physicalMass) r.physicalMass += m;
  const double need = targetDt / safety;  // required L_e/c_e
  for (const ElementKind* kind : elementKinds()) {
    const ScaledMass s = kind->scaleMass(model, need);
    r.scaledElements += s.elements;
    r.addedMass += s.added;
  }
  for (int i = 0; i < N.count; ++i)
    for (int k = 0; k < 3; ++k) N.invMassDof[3 * i + k] = 1.0 / N.mass[i];
  return r;
}

}  // namespace fsi::structure
