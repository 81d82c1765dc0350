#pragma once
// MembraneForces: internal forces of corotational constant-strain triangles.
//
// Kinematics. The reference triangle is stored in its own edge-aligned 2D frame (node 1 at the origin, node 2
// on the first axis); shape-function gradients live on this REFERENCE triangle (total Lagrangian), so the
// reference data never changes. The deformation gradient F (3x2) maps the reference plane onto the current
// triangle; its polar decomposition F = R U holds the element's rigid rotation R, which C = FᵀF = U² removes
// exactly. This is the corotational element with the exact (polar) rotation: no frame is built or stored.
// Strain: Green–Lagrange E = (C − I)/2, exactly zero for any rigid motion whatever the rotation angle.
// Stress: second Piola–Kirchhoff S from the wrinkling St Venant–Kirchhoff law (WrinklingMembrane.hpp).
// Forces: f_a = t A0 F S ∇N_a (one-point rule, reference area and thickness), rotated back to global axes.
// Optional viscous stress (Rayleigh β and linear bulk viscosity b1) from Ė = sym(FᵀḞ).
// The kinematics and the law live in MembraneKinematics.hpp (shared with the output and the stiffness
// bounds); the rest of the element kind (mass, scaling, fields, diagnosis) in MembraneElement.
// Evaluation: batches of lanes::kWidth triangles in vector lanes (MembraneBatch.hpp), the per-element loop
// for each block's remainder and as the reference. Splits into contiguous element ranges (whole batches) for
// threads (by effects/ThreadedForces.hpp, from the triangles' connectivity).

#include <cstdint>
#include <vector>

#include "structure/effects/Effect.hpp"
#include "structure/elements/ElementKind.hpp"
#include "structure/model/Model.hpp"

namespace fsi::structure {

/// Stiffness-proportional Rayleigh damping S_v = β C:Ė and bulk viscosity S_v += b1 ρ c L_e tr(Ė) I (ρ, c the
/// element's density and wave speed after mass scaling).
using MembraneViscosity = ElementDamping;

/// Per-element results for output and diagnosis.
struct MembraneStressField {
  std::vector<double> cauchy;       ///< 6 per element, global axes, order xx yy zz xy yz xz [Pa]
  std::vector<double> principal;    ///< 2 per element: major, minor principal Cauchy stress [Pa]
  std::vector<double> state;        ///< WrinkleState as a number (0 taut, 1 wrinkled, 2 slack)
  std::vector<double> majorStrain;  ///< major principal Green–Lagrange strain
};

/// Which loop evaluates the triangles: batches of lanes::kWidth in vector lanes (MembraneBatch.hpp, the
/// default) or one element at a time (the reference the batched kernel is tested and benchmarked against).
enum class MembraneKernel { Batched, PerElement };

class MembraneForces final : public Effect {
 public:
  MembraneForces(const MembraneTriangles& elements, MembraneViscosity viscosity,
                 MembraneKernel kernel = MembraneKernel::Batched);
  std::string name() const override { return "membrane"; }
  void addForces(ForceContext& ctx) const override;
  /// The triangles, 3 nodes each, in batches of the kernel's width.
  Connectivity connectivity() const override;
  void addRange(ForceContext& ctx, int begin, int end) const override;
  /// Stresses, states and strains at configuration x (no forces); used at output times.
  void evaluate(const double* x, MembraneStressField& out) const;

 private:
  const MembraneTriangles& el_;
  MembraneViscosity visc_;
  MembraneKernel kernel_;
};

/// Stresses, states and strains of every triangle at configuration x (the output fields and stress probes).
void membraneStresses(const MembraneTriangles& elements, const double* x, MembraneStressField& out);

}  // namespace fsi::structure
