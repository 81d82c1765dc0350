#include "coupling/mapping/projection/ProjectionRows.hpp"

#include <algorithm>

namespace fsi::coupling {

namespace {

L2Projection::SparseRows fromCsr(int rows, int cols, const std::vector<int>& outer,
                                 const std::vector<int>& inner, const std::vector<double>& values) {
  const Eigen::Map<const L2Projection::SparseRows> map(rows, cols, long(values.size()), outer.data(),
                                                       inner.data(), values.data());
  return L2Projection::SparseRows(map);
}

}  // namespace

void RowAccumulator::emit(std::vector<int>& inner, std::vector<double>& values) {
  std::sort(touched.begin(), touched.end());
  for (int col : touched) {
    inner.push_back(col);
    values.push_back(value[std::size_t(col)]);
  }
  touched.clear();
}

RowAssembly::RowAssembly(const ProjectionSetup& setup, bool unitDiagonal, ProjectionReport& report)
    : setup_(setup),
      unitDiagonal_(unitDiagonal),
      report_(report),
      nt_(setup.target.numPoints()),
      ns_(setup.source.numPoints()),
      accM_(nt_),
      accC_(ns_) {
  mOuter_.reserve(std::size_t(nt_) + 1);
  cOuter_.reserve(std::size_t(nt_) + 1);
  lumped_.resize(nt_);
  nodeMapped_.assign(std::size_t(nt_), 1);
}

void RowAssembly::addSource(int i, long q, double w) {
  const SourcePoints& sp = setup_.sources;
  const int t = sp.triangle[std::size_t(q)];
  setup_.sourceFan.forEachWeight(t, sp.bary[std::size_t(q)],
                                 [&](int k, double phi) { accC_.add(i, k, w * phi); });
  if (!setup_.gradient) return;
  const std::array<double, 3>& d = sp.gap[std::size_t(q)];
  if (negligibleGap(d, setup_.sourceEdge)) return;
  for (const GapGradient::Entry* e = setup_.gradient->begin(t); e != setup_.gradient->end(t); ++e)
    accC_.add(i, e->node, w * (d[0] * e->g[0] + d[1] * e->g[1] + d[2] * e->g[2]));
}

void RowAssembly::finishRow(int i, double rowSum, bool unmapped) {
  if (!(rowSum > 0.0)) {
    // No support of positive area: the node gets no value (0). A unit diagonal keeps M_t definite.
    unmapped = true;
    accM_.discard();
    accC_.discard();
    if (unitDiagonal_) accM_.add(i, i, 1.0);
    rowSum = 0.0;
  }
  lumped_[i] = rowSum;
  accM_.emit(mInner_, mValues_);
  accC_.emit(cInner_, cValues_);
  mOuter_.push_back(int(mInner_.size()));
  cOuter_.push_back(int(cInner_.size()));
  if (unmapped) {
    nodeMapped_[std::size_t(i)] = 0;
    if (report_.firstUnmappedNodes.size() < ProjectionReport::kListed)
      report_.firstUnmappedNodes.push_back(i);
    ++report_.unmappedTargetNodes;
  }
}

ProjectionRows RowAssembly::finish() {
  ProjectionRows rows;
  rows.m = fromCsr(nt_, nt_, mOuter_, mInner_, mValues_);
  rows.c = fromCsr(nt_, ns_, cOuter_, cInner_, cValues_);
  rows.lumped = std::move(lumped_);
  rows.nodeMapped = std::move(nodeMapped_);
  return rows;
}

ProjectionRows assembleNodalRows(const ProjectionSetup& setup, bool unitDiagonal, ProjectionReport& report) {
  const FanTriangulation& tf = setup.targetFan;
  const std::vector<QuadPoint>& qp = setup.points;
  const std::vector<int>& srcTri = setup.sources.triangle;
  const int nt = setup.target.numPoints();
  const long nq = long(qp.size());
  RowAssembly rows(setup, unitDiagonal, report);
  // Target node → (quadrature point, N_i there), in CSR form, so that each row of M_t and C is assembled
  // in one pass with a sparse accumulator (memory ∝ nnz, no triplet lists).
  std::vector<int> adjStart(std::size_t(nt) + 1, 0);
  for (const QuadPoint& p : qp)
    tf.forEachWeight(p.triangle, p.bary, [&](int i, double) { ++adjStart[std::size_t(i) + 1]; });
  for (int i = 0; i < nt; ++i) adjStart[std::size_t(i) + 1] += adjStart[std::size_t(i)];
  std::vector<int> adjPoint(std::size_t(adjStart.back()));
  std::vector<double> adjN(std::size_t(adjStart.back()));
  {
    std::vector<int> fill(adjStart.begin(), adjStart.end() - 1);
    for (long q = 0; q < nq; ++q) {
      const QuadPoint& p = qp[std::size_t(q)];
      tf.forEachWeight(p.triangle, p.bary, [&](int i, double n) {
        const int slot = fill[std::size_t(i)]++;
        adjPoint[std::size_t(slot)] = int(q);
        adjN[std::size_t(slot)] = n;
      });
    }
  }
  for (int i = 0; i < nt; ++i) {
    double rowSum = 0.0;
    bool unmapped = false;
    for (int a = adjStart[std::size_t(i)]; a < adjStart[std::size_t(i) + 1]; ++a) {
      const int q = adjPoint[std::size_t(a)];
      const QuadPoint& p = qp[std::size_t(q)];
      const double wi = p.weight * adjN[std::size_t(a)];
      rowSum += wi;
      tf.forEachWeight(p.triangle, p.bary, [&](int j, double n) { rows.addMass(i, j, wi * n); });
      if (srcTri[std::size_t(q)] >= 0)
        rows.addSource(i, q, wi);
      else
        unmapped = true;
    }
    rows.finishRow(i, rowSum, unmapped);
  }
  return rows.finish();
}

}  // namespace fsi::coupling
