#pragma once
// Kinematic constraints. Fixed dofs cost nothing in the step loop: their inverse mass is set to zero, so the
// update leaves them at rest. Prescribed motions, sliding on an oblique plane and tie groups are small
// post-passes over their own node lists (nothing runs when a scene has none).

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

/// Tie groups (`extrude`): a 2D model built as a strip of elements one element wide along an extrusion
/// direction d. The nodes of a group (equal coordinates apart from the one along d) move as one across d: the
/// tied part t(r) = mask ⊙ (r − (d·r) d) of their displacement and velocity is the group's, the part along d
/// stays each node's own. mask_k = 0 for a component d_k = 0 that every node of the group has fixed (then
/// nothing ties it). The integrators advance a group with its summed mass and force (see CentralDifference);
/// that is the M-orthogonal projection of the free update onto the tied motions, so the element step bound
/// of the untied structure still bounds it (Rayleigh quotients over a subspace). Tie forces are internal:
/// they sum to zero over a group and do no work on tied motions.
struct TieGroups {
  std::vector<int> start{0};  ///< group g holds nodes[start[g] .. start[g+1])
  std::vector<int> nodes;
  std::vector<std::array<double, 3>> direction;  ///< unit d per group
  std::vector<std::array<double, 3>> mask;       ///< 1 tied, 0 not (see above), per group

  int groups() const { return static_cast<int>(start.size()) - 1; }
  bool empty() const { return nodes.empty(); }
  void add(const std::vector<int>& groupNodes, const std::array<double, 3>& d,
           const std::array<double, 3>& tiedMask) {
    nodes.insert(nodes.end(), groupNodes.begin(), groupNodes.end());
    start.push_back(static_cast<int>(nodes.size()));
    direction.push_back(d);
    mask.push_back(tiedMask);
  }
  /// t(r) of group g.
  void tiedPart(int g, const double* r, double* t) const {
    const auto& d = direction[std::size_t(g)];
    const auto& m = mask[std::size_t(g)];
    const double along = r[0] * d[0] + r[1] * d[1] + r[2] * d[2];
    for (int k = 0; k < 3; ++k) t[k] = m[k] * (r[k] - along * d[k]);
  }
  /// Replaces the tied part of every group member's r (3 per node) by its share m_i/Σm of the group's total
  /// Σ t(r_j). For node forces: the out-of-balance force f_ext − f_int of a free node is its m·a; a tied node
  /// accelerates with its group, so its share is the m_i·a it actually has, and the tie forces (which make
  /// up the rest) are left out. At a static state the shares are zero.
  void shareByMass(const double* mass, double* r) const;
  /// Replaces the tied part of every member's velocity by the group's mass-weighted mean (momentum kept),
  /// and moves x by dt times that change (as PlaneSlider::project; dynamic relaxation with dt = 1). x may be
  /// null.
  void project(const double* mass, double* v, double* x, double dt) const;
  /// The same for the displacement x − X (a start whose rows were moved apart).
  void projectDisplacement(const double* mass, const double* X, double* x) const;
};

struct Constraints {
  std::vector<int> fixedDofs;  ///< 3*node + component
  std::vector<PrescribedMotion> prescribed;
  std::vector<PlaneSlider> sliders;
  TieGroups ties;

  /// Zeroes the inverse mass of fixed and prescribed dofs and the velocity of fixed dofs; gives the nodes of
  /// a tie group the group's mass-weighted mean tied displacement and velocity (momentum kept: a start
  /// whose rows move differently becomes the tied motion with the same momentum).
  void applyTo(Nodes& nodes) const;
  /// The reaction f_int − f_ext of every node (3 per node), with the tie forces left out (TieGroups::
  /// shareByMass with the nodes' masses): what `reaction` probes sum. Without tie groups, f_int − f_ext.
  void reactions(const Nodes& nodes, std::vector<double>& r) const;
};

/// Whether any node is held (fixed, prescribed or sliding on a plane): without, the structure has rigid-body
/// modes (ties alone couple nodes to each other, not to the ground).
inline bool hasSupport(const Constraints& c) {
  return !c.fixedDofs.empty() || !c.prescribed.empty() || !c.sliders.empty();
}

}  // namespace fsi::structure
