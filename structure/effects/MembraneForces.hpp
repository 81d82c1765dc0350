#pragma once
// MembraneForces: internal forces of corotational constant-strain triangles.
//
// Kinematics. Each triangle carries its own frame, rebuilt every step from the current nodes (e1 along edge
// 1-2, e2 in-plane, normal e1 x e2). The in-plane deformation gradient F maps the reference triangle, stored
// in its own edge-aligned frame, onto the current one expressed in the current frame; it is upper triangular.
// Shape-function gradients live on the REFERENCE triangle (total Lagrangian), so no update of the reference
// data is ever needed.
// Strain: Green–Lagrange E = (FᵀF − I)/2, exactly zero for any rigid motion whatever the rotation angle.
// Stress: second Piola–Kirchhoff S from the wrinkling St Venant–Kirchhoff law (WrinklingMembrane.hpp).
// Forces: f_a = t A0 F S ∇N_a (one-point rule, reference area and thickness), rotated back to global axes.
// Optional viscous stress (Rayleigh β and linear bulk viscosity b1) from Ė = sym(FᵀḞ).

#include <cstdint>
#include <vector>

#include "structure/effects/Effect.hpp"
#include "structure/model/Model.hpp"

namespace fsi::structure {

struct MembraneViscosity {
  double beta = 0;    ///< stiffness-proportional Rayleigh damping [s]: S_v = β C:Ė
  double bulkB1 = 0;  ///< linear bulk viscosity coefficient: S_v += b1 ρ c L_e tr(Ė) I
  bool enabled() const { return beta > 0 || bulkB1 > 0; }
};

/// Per-element results for output and diagnosis.
struct MembraneStressField {
  std::vector<double> cauchy;     ///< 6 per element, global axes, order xx yy zz xy yz xz [Pa]
  std::vector<double> principal;  ///< 2 per element: major, minor principal Cauchy stress [Pa]
  std::vector<double> state;      ///< WrinkleState as a number (0 taut, 1 wrinkled, 2 slack)
  std::vector<double> majorStrain;  ///< major principal Green–Lagrange strain
};

class MembraneForces final : public Effect {
 public:
  MembraneForces(const MembraneTriangles& elements, MembraneViscosity viscosity);
  std::string name() const override { return "membrane"; }
  void addForces(ForceContext& ctx) const override;
  /// Stresses, states and strains at configuration x (no forces); used at output times.
  void evaluate(const double* x, MembraneStressField& out) const;

 private:
  const MembraneTriangles& el_;
  MembraneViscosity visc_;
};

}  // namespace fsi::structure
