#pragma once
// The conservative transfer of a pressure given on another code's surface (a SurfaceField) onto a set of the
// structure's triangles, set up and applied once at load time.
//
// With L2Projection from the triangles (source) to the file's surface (target), C_ji = ∫_file N_j φ_i(P(x))
// (P: closest point on the triangles), the conservative transfer Hᵀ (lumped variant, H = diag(M_f 1)⁻¹ C)
// carries the file's nodal loads diag(M_f 1) p_f to the triangles' nodes: g = Cᵀ p_f,
// g_i = ∫_file p φ_i(P(x)) dΓ (p linear on the file's faces). The nodal pressure on the
// triangles solves M_s p_s = g (their consistent mass matrix: a linear field is reproduced), and each
// triangle takes the mean of its three nodes. Then Σ_e A_e p_e = 1ᵀ M_s p_s = Σ g = ∫_file p dΓ: the
// integral of the pressure is carried over to round-off, so the resultant on a flat surface is exactly the
// file's; on a curved one it agrees to discretisation error (the two surfaces' normals differ).

#include <functional>
#include <string>
#include <vector>

#include "coupling/effects/PressureFieldFiles.hpp"
#include "coupling/interface/InterfaceMesh.hpp"

namespace fsi::coupling {

/// One pressure per face of `triangles` (a triangle-only mesh). The file's surface must lie within
/// `tolerance` of the triangles everywhere, and must cover every triangle node's neighbourhood (at least half
/// of the node's area receives data); otherwise fsi::InputError names the first offending point of the
/// file, or the node (through `describeNode`, given the local point index).
std::vector<double> conservativeTrianglePressure(const InterfaceMesh& triangles, const SurfaceField& source,
                                                 double tolerance,
                                                 const std::function<std::string(int)>& describeNode);

/// The CONSISTENT alternative (`projection: consistent`): L2Projection from the file's surface to the
/// triangles, p_s = M_s⁻¹ C p_f with C_ij = ∫_triangles N_i φ_j(P(x)) (P: closest point on the file's
/// surface), each triangle the mean of its nodes. Reproduces constant and linear fields exactly (a uniform
/// pressure on a closed skin has no resultant, whatever the two surfaces' areas), and samples only where the
/// triangles are, so the file may cover more than the set (a whole-wing surface for `wing/upper`); the
/// integral of p is not conserved. Every quadrature point of the triangles must lie within `tolerance` of the
/// file's surface; otherwise fsi::InputError names the first one.
std::vector<double> consistentTrianglePressure(const InterfaceMesh& triangles, const SurfaceField& source,
                                               double tolerance,
                                               const std::function<std::string(int)>& describeNode);

/// ∫ p dΓ of a field on its own surface, linear on every fan triangle (the integral the transfer keeps).
double surfaceIntegral(const SurfaceField& field);

}  // namespace fsi::coupling
