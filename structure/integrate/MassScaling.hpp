#pragma once
// Selective mass scaling: elements whose stable step (reference geometry) is below a target get a larger
// density, just enough to reach it. A few tiny elements then no longer dictate the step of the whole mesh.
// The added mass changes the dynamics, so it is reported; gravity keeps using the physical mass.

#include "structure/model/Model.hpp"

namespace fsi::structure {

struct MassScalingReport {
  int scaledElements = 0;
  double addedMass = 0;     ///< [kg]
  double physicalMass = 0;  ///< [kg]
  double addedFraction() const { return physicalMass > 0 ? addedMass / physicalMass : 0.0; }
};

/// Raises densities so that every element's L_e/c_e * safety >= targetDt. Updates masses, inverse masses
/// and wave speeds. Call before constraints are applied and before effects are created.
MassScalingReport applyMassScaling(Model& model, double targetDt, double safety);

/// Smallest reference-geometry stable step (L_e/c_e) over all elements, without safety factor.
double referenceStableDt(const Model& model);

}  // namespace fsi::structure
