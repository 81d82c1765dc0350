#include "coupling/effects/SurfacePressureMapping.hpp"

#include <fmt/format.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>

#include "coupling/interface/SurfaceSearch.hpp"
#include "coupling/mapping/L2Projection.hpp"
#include "structure/model/Error.hpp"

namespace fsi::coupling {

namespace {

double triangleArea(const std::array<double, 3>& a, const std::array<double, 3>& b,
                    const std::array<double, 3>& c) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

}  // namespace

double surfaceIntegral(const SurfaceField& field) {
  const FanTriangulation fan(field.mesh);
  double sum = 0;
  for (int t = 0; t < fan.numTriangles(); ++t)
    sum += fan.area(t) * fan.interpolate(t, {1.0 / 3, 1.0 / 3, 1.0 / 3}, field.values.data());
  return sum;
}

std::vector<double> conservativeTrianglePressure(const InterfaceMesh& tri, const SurfaceField& source,
                                                 double tolerance,
                                                 const std::function<std::string(int)>& describeNode) {
  if (int(source.values.size()) != source.mesh.numPoints())
    throw InputError(fmt::format("{}: {} values for {} points", source.mesh.name, source.values.size(),
                                 source.mesh.numPoints()));
  ProjectionOptions opt;
  // The lumped variant: the same C as the consistent one (which H = M_f⁻¹ C would only add a factorisation
  // of the file's mass matrix to), and Hᵀ applied to the lumped loads diag(M_f 1) p_f is Cᵀ p_f.
  opt.mass = MassMatrix::Lumped;
  opt.tolerance = tolerance;
  // Neither correction: both would make H something other than diag⁻¹ C (the defect correction) or give
  // C column sums other than the area each node receives data on (the gap correction's transport weights
  // sum to zero over a row, not over a column), and this mapping is defined by Cᵀ p_f and Cᵀ 1.
  opt.gapCorrection = false;
  opt.defectCorrection = ProjectionOptions::Defect::Off;
  // C is integrated over the file's surface, and the triangles' shape functions bend at their edges inside
  // the file's faces: the quadrature cells are made about a quarter of a triangle edge (level 1 for a file
  // four times finer than the triangles, the usual CFD surface), so that every node receives its share.
  const double ratio = source.mesh.meanEdgeLength() / std::max(tri.meanEdgeLength(), 1e-300);
  opt.quadratureLevel = int(std::clamp(std::ceil(4.0 * ratio), 1.0, 32.0));
  const L2Projection proj(tri, source.mesh, opt);
  const ProjectionReport& rep = proj.report();
  if (rep.unmappedQuadraturePoints > 0) {
    const UnmappedPoint& u = rep.firstUnmappedPoints.front();
    throw InputError(fmt::format(
        "{}: {} of {} quadrature points of the file's surface are farther than the tolerance {:g} m from the "
        "triangles (first at ({:g}, {:g}, {:g}), {:g} m away): the file must cover the same surface as the "
        "triangle set (crop it to that part, choose the matching set, or raise `tolerance`)",
        source.mesh.name, rep.unmappedQuadraturePoints, rep.quadraturePoints, tolerance, u.x[0], u.x[1],
        u.x[2], u.distance));
  }
  const int n = tri.numPoints();
  // g = Hᵀ (M_f p_f) = Cᵀ p_f, and the area each node receives data on, w = Cᵀ 1 = Hᵀ (M_f 1).
  const Eigen::VectorXd& mf = proj.lumpedMass();
  Eigen::VectorXd loads(mf.size()), g(n), w(n);
  for (Eigen::Index j = 0; j < mf.size(); ++j) loads[j] = mf[j] * source.values[std::size_t(j)];
  proj.applyTranspose(loads, g);
  proj.applyTranspose(mf, w);

  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd lumped = Eigen::VectorXd::Zero(n);
  for (int f = 0; f < tri.numFaces(); ++f) {
    if (tri.faceSize(f) != 3) throw std::logic_error("conservativeTrianglePressure: triangles only");
    const int* v = tri.face(f);
    const double a = triangleArea(tri.points[std::size_t(v[0])], tri.points[std::size_t(v[1])],
                                  tri.points[std::size_t(v[2])]);
    for (int i = 0; i < 3; ++i) {
      lumped[v[i]] += a / 3;
      for (int j = 0; j < 3; ++j) entries.emplace_back(v[i], v[j], a * (i == j ? 2.0 : 1.0) / 12.0);
    }
  }
  for (int i = 0; i < n; ++i)
    if (!(w[i] >= 0.5 * lumped[i]))
      throw InputError(fmt::format(
          "{}: the file's surface does not cover {} at ({:g}, {:g}, {:g}): data reach {:.0f} % of its area "
          "(the file must cover the whole triangle set; nothing is extrapolated)",
          source.mesh.name, describeNode(i), tri.points[std::size_t(i)][0], tri.points[std::size_t(i)][1],
          tri.points[std::size_t(i)][2], lumped[i] > 0 ? 100.0 * w[i] / lumped[i] : 0.0));
  Eigen::SparseMatrix<double> m(n, n);
  m.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(m);
  if (ldlt.info() != Eigen::Success)
    throw InputError(
        fmt::format("{}: the triangles' mass matrix is singular (degenerate triangles)", source.mesh.name));
  const Eigen::VectorXd ps = ldlt.solve(g);
  std::vector<double> p(std::size_t(tri.numFaces()));
  for (int f = 0; f < tri.numFaces(); ++f) {
    const int* v = tri.face(f);
    p[std::size_t(f)] = (ps[v[0]] + ps[v[1]] + ps[v[2]]) / 3.0;
  }
  return p;
}

std::vector<double> consistentTrianglePressure(const InterfaceMesh& tri, const SurfaceField& source,
                                               double tolerance,
                                               const std::function<std::string(int)>& describeNode) {
  if (int(source.values.size()) != source.mesh.numPoints())
    throw InputError(fmt::format("{}: {} values for {} points", source.mesh.name, source.values.size(),
                                 source.mesh.numPoints()));
  ProjectionOptions opt;
  opt.mass = MassMatrix::Consistent;
  opt.tolerance = tolerance;
  // C is integrated over the triangles: about as many quadrature points as the file has nodes there, so
  // that a finer file is sampled rather than skipped (linear fields are exact at any level).
  const double ratio = tri.meanEdgeLength() / std::max(source.mesh.meanEdgeLength(), 1e-300);
  opt.quadratureLevel = int(std::clamp(std::ceil(ratio), 1.0, 8.0));
  const L2Projection proj(source.mesh, tri, opt);
  const ProjectionReport& rep = proj.report();
  if (rep.unmappedQuadraturePoints > 0) {
    const UnmappedPoint& u = rep.firstUnmappedPoints.front();
    throw InputError(fmt::format(
        "{}: {} of {} quadrature points of the triangles are farther than the tolerance {:g} m from the "
        "file's "
        "surface (first at ({:g}, {:g}, {:g}), {:g} m away{}): the file must cover the whole triangle set "
        "(nothing is extrapolated)",
        source.mesh.name, rep.unmappedQuadraturePoints, rep.quadraturePoints, tolerance, u.x[0], u.x[1],
        u.x[2], u.distance,
        rep.firstUnmappedNodes.empty()
            ? ""
            : ", in the support of " + describeNode(rep.firstUnmappedNodes.front())));
  }
  if (rep.unmappedTargetNodes > 0)
    throw InputError(fmt::format("{}: {} receives no data (it belongs to no triangle of positive area)",
                                 source.mesh.name, describeNode(rep.firstUnmappedNodes.front())));
  std::vector<double> ps(std::size_t(tri.numPoints()));
  proj.apply(source.values.data(), ps.data());
  std::vector<double> p(std::size_t(tri.numFaces()));
  for (int f = 0; f < tri.numFaces(); ++f) {
    const int* v = tri.face(f);
    p[std::size_t(f)] = (ps[std::size_t(v[0])] + ps[std::size_t(v[1])] + ps[std::size_t(v[2])]) / 3.0;
  }
  return p;
}

}  // namespace fsi::coupling
