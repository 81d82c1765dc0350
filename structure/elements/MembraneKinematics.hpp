#pragma once
// Kinematics and stress of one constant-strain membrane triangle, shared by everything that looks inside a
// triangle: the force kernel (MembraneForces), the output fields and the tangent-stiffness bounds of dynamic
// relaxation (MembraneElement). One definition, so a change of the element's kinematics or law reaches all.
//
// The reference triangle is stored in its own edge-aligned 2D frame (node 1 at the origin, node 2 on the
// first axis). F (3x2) maps the reference plane onto the current triangle; C = FᵀF removes the element's
// rotation exactly, so the frame of the current triangle is never built (corotational with the polar
// rotation).

#include <algorithm>
#include <cmath>

#include "structure/material/WrinklingMembrane.hpp"
#include "structure/model/Model.hpp"

namespace fsi::structure::membrane {

// In-plane deformation gradient F = [f1 f2]: the images of the reference tangent axes.
struct Kinematics {
  double d21[3], d31[3];      // current edge vectors from node 1
  double f1[3], f2[3];        // columns of F
  double n2x, n2y, n3y, tA0;  // reference shape-function gradients (node 1 = −node 2 − node 3) and t·A0
  double C11, C12, C22;       // right Cauchy–Green tensor
};

inline void kinematics(const double* __restrict x, const int* n, const double* __restrict g, Kinematics& k) {
  const double* p1 = x + 3 * n[0];
  const double* p2 = x + 3 * n[1];
  const double* p3 = x + 3 * n[2];
  k.n2x = g[0];
  k.n2y = -g[1] * g[0] * g[2];
  k.n3y = g[2];
  k.tA0 = g[3];
  for (int i = 0; i < 3; ++i) {
    k.d21[i] = p2[i] - p1[i];
    k.d31[i] = p3[i] - p1[i];
    k.f1[i] = k.d21[i] * k.n2x;
    k.f2[i] = k.d21[i] * k.n2y + k.d31[i] * k.n3y;
  }
  k.C11 = k.f1[0] * k.f1[0] + k.f1[1] * k.f1[1] + k.f1[2] * k.f1[2];
  k.C12 = k.f1[0] * k.f2[0] + k.f1[1] * k.f2[1] + k.f1[2] * k.f2[2];
  k.C22 = k.f2[0] * k.f2[0] + k.f2[1] * k.f2[1] + k.f2[2] * k.f2[2];
}

/// Reference shape-function gradients ∇N_a (a = node 1..3, components along the reference axes).
inline void shapeGradients(const Kinematics& k, double G[3][2]) {
  G[1][0] = k.n2x, G[1][1] = k.n2y;
  G[2][0] = 0.0, G[2][1] = k.n3y;
  G[0][0] = -k.n2x, G[0][1] = -k.n2y - k.n3y;
}

/// Green–Lagrange strain (E11, E22, 2E12) of the element.
inline void greenStrain(const Kinematics& k, double& e11, double& e22, double& g12) {
  e11 = 0.5 * (k.C11 - 1.0), e22 = 0.5 * (k.C22 - 1.0), g12 = k.C12;
}

/// Second Piola–Kirchhoff stress of the block's law (wrinkling or plain St Venant–Kirchhoff) and the strain
/// energy density w.
template <bool Wrinkling>
inline WrinkleState stress(const Kinematics& k, const MembraneBlock& blk, double S[3], double& w) {
  double e11, e22, g12;
  greenStrain(k, e11, e22, g12);
  if constexpr (Wrinkling) {
    return wrinklingStress(e11, e22, g12, blk.young, blk.c11, blk.poisson, S, w);
  } else {
    return elasticStress(e11, e22, g12, blk.c11, blk.poisson, S, w);
  }
}

/// Stress of the taut (tension-and-compression) law whatever the block's setting: the tangent of the plain
/// St Venant–Kirchhoff law bounds the wrinkling one, which is what the stiffness bounds need.
inline void tautStress(const Kinematics& k, const MembraneBlock& blk, double S[3]) {
  double e11, e22, g12, w;
  greenStrain(k, e11, e22, g12);
  elasticStress(e11, e22, g12, blk.c11, blk.poisson, S, w);
}

}  // namespace fsi::structure::membrane
