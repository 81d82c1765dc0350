// laplace: the membrane's normal equilibrium at a node, measured from the deformed shape and the stresses.
// A membrane carries a normal pressure p only through its curvature: p = N : b = N₁₁b₁₁ + 2N₁₂b₁₂ + N₂₂b₂₂
// (Young–Laplace; N the stress resultant [N/m], b the curvature tensor of the current surface). For a
// bulge between two ribs this is the relation T ≈ Δp·r when the other direction's term is negligible.
// The probe fits a quadric to the nodes of a patch of `rings` rings around the node (default 2: curvature),
// averages the stress resultant over the same patch (area-weighted), and takes p from the applied load on the
// node over its tributary area, so it checks the discrete solution against the continuum law without knowing
// which loads act. Quantities: ratio = (N:b)/p (1 in the limit), simple_ratio = N_dd·b_dd/p (the
// one-direction bulge relation T/(p·r) along `direction`), radius = 1/b_dd, tension = N_dd, pressure = p.
#include "structure/probes/LaplaceProbe.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "structure/probes/ProbeKinds.hpp"

namespace fsi::structure {

namespace {

void neighbourhood(const MembraneTriangles& T, const std::vector<int>& set, int node, int rings,
                   std::vector<int>& own, std::vector<int>& patch, std::vector<int>& ring);

using V3 = Eigen::Vector3d;

V3 at(const std::vector<double>& x, int n) {
  return {x[3 * n], x[3 * n + 1], x[3 * n + 2]};
}

// Membrane thickness of element e from its reference data (geo = 1/a0, b0, 1/c0, t·A0; A0 = a0·c0/2).
double thickness(const MembraneTriangles& T, int e) {
  const double* g = &T.geo[MembraneTriangles::kGeo * e];
  return 2.0 * g[3] * g[0] * g[2];
}

// The node's own triangles in the set (`own`), and the patch `rings` rings around it: its triangles
// (`patch`) and their nodes other than the node itself (`ring`).
void neighbourhood(const MembraneTriangles& T, const std::vector<int>& set, int node, int rings,
                   std::vector<int>& own, std::vector<int>& patch, std::vector<int>& ring) {
  own.clear();
  for (int e : set)
    for (int k = 0; k < 3; ++k)
      if (T.conn[3 * e + k] == node) own.push_back(e);
  std::vector<int> reached{node};
  for (int r = 0; r < rings; ++r) {
    patch.clear();
    for (int e : set)
      for (int k = 0; k < 3; ++k)
        if (std::binary_search(reached.begin(), reached.end(), T.conn[3 * e + k])) {
          patch.push_back(e);
          break;
        }
    for (int e : patch)
      for (int k = 0; k < 3; ++k) reached.push_back(T.conn[3 * e + k]);
    std::sort(reached.begin(), reached.end());
    reached.erase(std::unique(reached.begin(), reached.end()), reached.end());
  }
  ring = reached;
  ring.erase(std::remove(ring.begin(), ring.end(), node), ring.end());
}

double evaluateAt(const ProbeSpec& p, ProbeState& state, int node) {
  const Model& model = state.model();
  const Nodes& N = model.nodes;
  const MembraneTriangles& T = model.membranes;
  std::vector<int> tris, patch, ring;
  neighbourhood(T, p.triangles, node, p.rings, tris, patch, ring);
  if (tris.empty() || ring.size() < 6) return std::nan("");
  const V3 x0 = at(N.x, node);
  // Normal and tributary area from the node's triangles (their orientation gives the normal's sign).
  V3 normal = V3::Zero();
  double area = 0;
  for (int e : tris) {
    const V3 a = at(N.x, T.conn[3 * e]), b = at(N.x, T.conn[3 * e + 1]), c = at(N.x, T.conn[3 * e + 2]);
    const V3 n2 = (b - a).cross(c - a);
    normal += n2;
    area += 0.5 * n2.norm();
  }
  if (!(normal.norm() > 0)) return std::nan("");
  normal.normalize();
  // Quadric w = ½a u² + b uv + ½c v² + d u + e v + f in the tangent frame, a least-squares fit over the
  // patch: not forced through the node, so a fold or zigzag at element scale (a wrinkled membrane) does not
  // become the curvature. The fitted slope (d, e) tilts the normal and the fit is repeated (b to second
  // order).
  Eigen::Vector2d slope;
  Eigen::Matrix2d hess;
  V3 e1, e2;
  for (int pass = 0; pass < 3; ++pass) {
    e1 = (std::abs(normal.x()) < 0.9 ? V3::UnitX() : V3::UnitY()).cross(normal).normalized();
    e2 = normal.cross(e1);
    Eigen::MatrixXd A(ring.size() + 1, 6);
    Eigen::VectorXd w(ring.size() + 1);
    A.row(Eigen::Index(ring.size())) << 0, 0, 0, 0, 0, 1;  // the node itself
    w(Eigen::Index(ring.size())) = 0;
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const V3 r = at(N.x, ring[i]) - x0;
      const double u = r.dot(e1), v = r.dot(e2);
      A.row(Eigen::Index(i)) << 0.5 * u * u, u * v, 0.5 * v * v, u, v, 1;
      w(Eigen::Index(i)) = r.dot(normal);
    }
    const Eigen::VectorXd c = A.colPivHouseholderQr().solve(w);
    hess << c(0), c(1), c(1), c(2);
    slope << c(3), c(4);
    normal = (normal - slope(0) * e1 - slope(1) * e2).normalized();
  }
  // A surface that bends away from its normal (a bulge seen from outside) has positive curvature here.
  const Eigen::Matrix2d b = -hess / std::pow(1.0 + slope.squaredNorm(), 1.5);
  // Stress resultant N = σ·t (Cauchy stress, force per current length), area-averaged over the patch: in a
  // wrinkled region neighbouring triangles carry their tension in different directions, their mean is the
  // resultant the mean surface carries.
  const MembraneStressField& s = state.membraneStress();
  Eigen::Matrix3d Nres = Eigen::Matrix3d::Zero();
  double wsum = 0;
  for (int e : patch) {
    const double* c = &s.cauchy[6 * e];
    Eigen::Matrix3d sig;
    sig << c[0], c[3], c[5], c[3], c[1], c[4], c[5], c[4], c[2];
    const V3 a = at(N.x, T.conn[3 * e]), bb = at(N.x, T.conn[3 * e + 1]), cc = at(N.x, T.conn[3 * e + 2]);
    const double ae = 0.5 * (bb - a).cross(cc - a).norm();
    Nres += ae * thickness(T, e) * sig;
    wsum += ae;
  }
  Nres /= wsum;
  Eigen::Matrix<double, 3, 2> E;
  E.col(0) = e1;
  E.col(1) = e2;
  const Eigen::Matrix2d n2 = E.transpose() * Nres * E;
  // The applied normal pressure, positive outward: the load on the node over its third of the triangles.
  const double pressure = normal.dot(at(N.fext, node)) / (area / 3.0);
  const double nb = (n2.array() * b.array()).sum();
  if (p.laplace == LaplaceQuantity::Ratio) return nb / pressure;
  if (p.laplace == LaplaceQuantity::Pressure) return pressure;
  V3 d(p.direction[0], p.direction[1], p.direction[2]);
  d -= d.dot(normal) * normal;
  if (!(d.norm() > 1e-12)) return std::nan("");
  d.normalize();
  const Eigen::Vector2d dl(d.dot(e1), d.dot(e2));
  const double bdd = dl.dot(b * dl), ndd = dl.dot(n2 * dl);
  switch (p.laplace) {
    case LaplaceQuantity::Radius:
      return 1.0 / bdd;
    case LaplaceQuantity::Tension:
      return ndd;
    default:
      return ndd * bdd / pressure;
  }
}

void evaluate(const ProbeSpec& p, ProbeState& state, std::vector<double>& vals) {
  for (int n : p.nodes) vals.push_back(evaluateAt(p, state, n));
}

}  // namespace

std::string laplaceFitProblem(const Model& model, const std::vector<int>& triangles, int node, int rings) {
  // The fit needs the node inside the surface (every edge at it shared by two of the triangles: a fit from
  // one side of an edge extrapolates) and at least 6 neighbours, the quadric's unknowns.
  std::vector<int> tris, patch, ring;
  neighbourhood(model.membranes, triangles, node, rings, tris, patch, ring);
  std::vector<int> edgeEnds;
  for (int e : tris)
    for (int k = 0; k < 3; ++k)
      if (model.membranes.conn[3 * e + k] != node) edgeEnds.push_back(model.membranes.conn[3 * e + k]);
  std::sort(edgeEnds.begin(), edgeEnds.end());
  bool inside = !edgeEnds.empty();
  for (std::size_t i = 0; i < edgeEnds.size(); ++i) {
    const bool paired = (i + 1 < edgeEnds.size() && edgeEnds[i + 1] == edgeEnds[i]) ||
                        (i > 0 && edgeEnds[i - 1] == edgeEnds[i]);
    inside = inside && paired;
  }
  if (inside && ring.size() >= 6) return "";
  return fmt::format(
      "node {} is {} of the probe's triangles ({} neighbours); the curvature fit needs a node "
      "inside the surface with at least 6 neighbours",
      model.nodes.tag[node], tris.empty() ? "not on any" : "on the edge", ring.size());
}

ProbeKind laplaceProbe() {
  return {
      "laplace",
      "membrane normal equilibrium at nodes: (N:b)/p from the fitted curvature, the stresses and the load",
      evaluate};
}

}  // namespace fsi::structure
