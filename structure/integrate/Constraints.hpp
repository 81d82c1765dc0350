#pragma once
// Kinematic constraints. Fixed dofs cost nothing in the step loop: their inverse mass is set to zero, so the
// update leaves them at rest. Prescribed motions and sliding on an oblique plane are small post-passes over
// their own node lists.

#include <array>
#include <vector>

#include "structure/effects/TimeFunction.hpp"
#include "structure/model/Model.hpp"

namespace fsi::structure {

struct PrescribedMotion {
  int node = 0;
  int component = 0;     ///< 0, 1, 2 = x, y, z
  double amplitude = 0;  ///< u(t) = amplitude·f(t) added to the reference coordinate
  TimeFunction fn;
};

/// A node that may only move within a plane (symmetry plane with an oblique normal).
struct PlaneSlider {
  int node = 0;
  std::array<double, 3> normal{0, 0, 1};  ///< unit normal

  /// After a step of size dt that moved the node by dt·v: removes the normal component vn of its velocity
  /// (v: the node's 3 values) and of that step from its position x. Returns vn. The one projection both
  /// integrators use (dynamic relaxation with dt = 1).
  double project(double* v, double* x, double dt) const {
    const double vn = v[0] * normal[0] + v[1] * normal[1] + v[2] * normal[2];
    for (int k = 0; k < 3; ++k) {
      v[k] -= vn * normal[k];
      x[k] -= dt * vn * normal[k];
    }
    return vn;
  }
};

struct Constraints {
  std::vector<int> fixedDofs;  ///< 3*node + component
  std::vector<PrescribedMotion> prescribed;
  std::vector<PlaneSlider> sliders;

  /// Zeroes the inverse mass of fixed and prescribed dofs and the velocity of fixed dofs.
  void applyTo(Nodes& nodes) const;
};

}  // namespace fsi::structure
