#include "coupling/mapping/projection/DualProjection.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <vector>

namespace fsi::coupling {

namespace {

// Every face's A_f (row-major, n_f² values from aOffset[f]) and D_f (n_f values, aligned with the face's
// nodes), the fan triangles of each face (consecutive: faceTri[f] .. faceTri[f + 1]) and the faces around
// each node (nodeFaces[nodeFaceStart[i]] ..).
struct DualFaces {
  std::vector<int> faceTri, nodeFaceStart, nodeFaces;
  std::vector<std::size_t> aOffset;
  std::vector<double> aValues, dValues;
};

DualFaces dualFaces(const InterfaceMesh& target, const FanTriangulation& tf) {
  const int nt = target.numPoints();
  DualFaces d;
  std::vector<int>& faceTri = d.faceTri;
  std::vector<int>& nodeFaceStart = d.nodeFaceStart;
  std::vector<int>& nodeFaces = d.nodeFaces;
  std::vector<std::size_t>& aOffset = d.aOffset;
  std::vector<double>& aValues = d.aValues;
  std::vector<double>& dValues = d.dValues;
  const int nf = target.numFaces();
  faceTri.assign(std::size_t(nf) + 1, 0);  // fan triangles of a face are consecutive
  for (int t = 0; t < tf.numTriangles(); ++t) ++faceTri[std::size_t(tf.triangleFace[std::size_t(t)]) + 1];
  for (int f = 0; f < nf; ++f) faceTri[std::size_t(f) + 1] += faceTri[std::size_t(f)];
  nodeFaceStart.assign(std::size_t(nt) + 1, 0);
  nodeFaces.resize(target.faceNodes.size());
  for (int n : target.faceNodes) ++nodeFaceStart[std::size_t(n) + 1];
  for (int i = 0; i < nt; ++i) nodeFaceStart[std::size_t(i) + 1] += nodeFaceStart[std::size_t(i)];
  {
    std::vector<int> fill(nodeFaceStart.begin(), nodeFaceStart.end() - 1);
    for (int f = 0; f < nf; ++f)
      for (int k = 0; k < target.faceSize(f); ++k)
        nodeFaces[std::size_t(fill[std::size_t(target.face(f)[k])]++)] = f;
  }
  // A_f (row-major, n_f² values) and D_f (n_f values, aligned with the face's nodes) for every face.
  aOffset.assign(std::size_t(nf) + 1, 0);
  for (int f = 0; f < nf; ++f)
    aOffset[std::size_t(f) + 1] =
        aOffset[std::size_t(f)] + std::size_t(target.faceSize(f) * target.faceSize(f));
  aValues.assign(aOffset.back(), 0.0);
  dValues.assign(target.faceNodes.size(), 0.0);
  Eigen::MatrixXd mf, minv;
  Eigen::VectorXd df;
  for (int f = 0; f < nf; ++f) {
    const int n = target.faceSize(f);
    const int* nodes = target.face(f);
    mf.setZero(n, n);
    for (int t = faceTri[std::size_t(f)]; t < faceTri[std::size_t(f) + 1]; ++t) {
      // Corner k of the fan triangle as weights over the face's nodes: one node, or 1/n each for the
      // centre.
      Eigen::Matrix<double, 3, Eigen::Dynamic> e = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, n);
      for (int k = 0; k < 3; ++k) {
        const int c = tf.triangles[std::size_t(t)][std::size_t(k)];
        if (c >= tf.numPoints) {
          e.row(k).setConstant(1.0 / n);
        } else {
          for (int b = 0; b < n; ++b)
            if (nodes[b] == c) {
              e(k, b) = 1.0;
              break;
            }
        }
      }
      Eigen::Matrix3d mt = Eigen::Matrix3d::Constant(1.0) + Eigen::Matrix3d::Identity();
      mt *= tf.area(t) / 12.0;
      mf.noalias() += e.transpose() * mt * e;
    }
    df = mf.rowwise().sum();
    Eigen::LLT<Eigen::MatrixXd> llt(mf);
    if (llt.info() != Eigen::Success || !(df.minCoeff() > 0.0)) continue;  // degenerate: no contribution
    minv = llt.solve(Eigen::MatrixXd::Identity(n, n));
    for (int a = 0; a < n; ++a) {
      dValues[std::size_t(target.faceOffsets[std::size_t(f)] + a)] = df(a);
      for (int b = 0; b < n; ++b)
        aValues[aOffset[std::size_t(f)] + std::size_t(a * n + b)] = df(a) * minv(a, b);
    }
  }
  return d;
}

// The rows of C_ψ, face by face around each target node.
ProjectionRows assembleDualRows(const ProjectionSetup& setup, ProjectionReport& report) {
  // Dual (biorthogonal) test functions (see the header): the rows of C_ψ, face by face around each
  // target node.
  const InterfaceMesh& target = setup.target;
  const FanTriangulation& tf = setup.targetFan;
  const std::vector<QuadPoint>& qp = setup.points;
  const std::vector<std::pair<int, double>>& perTriangle = setup.perTriangle;
  const std::vector<int>& srcTri = setup.sources.triangle;
  const int nt = target.numPoints(), level = setup.level;
  const DualFaces d = dualFaces(target, tf);
  const std::vector<int>& faceTri = d.faceTri;
  const std::vector<int>& nodeFaceStart = d.nodeFaceStart;
  const std::vector<int>& nodeFaces = d.nodeFaces;
  const std::vector<std::size_t>& aOffset = d.aOffset;
  const std::vector<double>& aValues = d.aValues;
  const std::vector<double>& dValues = d.dValues;
  RowAssembly rows(setup, /*unitDiagonal=*/false, report);
  const int perTri = 3 * level * (level + 1) / 2;
  for (int i = 0; i < nt; ++i) {
    double rowSum = 0.0;
    bool unmapped = false;
    for (int s = nodeFaceStart[std::size_t(i)]; s < nodeFaceStart[std::size_t(i) + 1]; ++s) {
      const int f = nodeFaces[std::size_t(s)];
      const int n = target.faceSize(f);
      const int* nodes = target.face(f);
      const int a = int(std::find(nodes, nodes + n, i) - nodes);
      rowSum += dValues[std::size_t(target.faceOffsets[std::size_t(f)] + a)];
      const double* arow = &aValues[aOffset[std::size_t(f)] + std::size_t(a * n)];
      for (int t = faceTri[std::size_t(f)]; t < faceTri[std::size_t(f) + 1]; ++t)
        for (int e = t * perTri; e < (t + 1) * perTri; ++e) {
          const auto [q, w] = perTriangle[std::size_t(e)];
          if (srcTri[std::size_t(q)] < 0) {
            unmapped = true;
            continue;
          }
          // ψ_i(q) from the N_b there; a point on the face's edge may belong to the neighbour's triangle,
          // where only the edge's end nodes (shared by both faces) are non-zero.
          double psi = 0.0;
          const QuadPoint& p = qp[std::size_t(q)];
          tf.forEachWeight(p.triangle, p.bary, [&](int node, double nv) {
            const int b = int(std::find(nodes, nodes + n, node) - nodes);
            if (b < n) psi += arow[b] * nv;
          });
          rows.addSource(i, q, w * psi);
        }
    }
    rows.finishRow(i, rowSum, unmapped);
  }
  return rows.finish();
}

}  // namespace

DualProjection::DualProjection(const ProjectionSetup& setup, ProjectionReport& report)
    : ProjectionVariant(assembleDualRows(setup, report)) {}

std::unique_ptr<ProjectionVariant> makeDualProjection(const ProjectionSetup& setup,
                                                      ProjectionReport& report) {
  return std::make_unique<DualProjection>(setup, report);
}

}  // namespace fsi::coupling
