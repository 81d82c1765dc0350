#include "coupling/mapping/projection/PointwiseEvaluation.hpp"

#include <Eigen/SparseCore>
#include <algorithm>
#include <vector>

namespace fsi::coupling {

PointwiseEvaluation::PointwiseEvaluation(const SurfaceSearch& search, const InterfaceMesh& target) {
  const int nt = target.numPoints(), ns = search.fan().numPoints;
  std::vector<Eigen::Triplet<double, int>> entries;
  entries.reserve(std::size_t(nt) * 4);
  nodeMapped_.assign(std::size_t(nt), 1);
  int hint = -1;
  for (int i = 0; i < nt; ++i) {
    const SurfacePoint p = search.closest(target.points[std::size_t(i)], hint);
    hint = p.triangle;
    if (!p.mapped) {
      nodeMapped_[std::size_t(i)] = 0;
      ++unmapped_;
      continue;
    }
    maxGap_ = std::max(maxGap_, p.distance);
    // A node equally close to several points of the surface (on a symmetry plane over a valley or a ridge)
    // takes their mean: the first one found would break the symmetry (docs/PROJECTION.md, "Ties").
    const std::vector<SurfacePoint> ties = search.equallyClose(target.points[std::size_t(i)], p);
    const double share = 1.0 / double(ties.size());
    for (const SurfacePoint& q : ties)
      search.fan().forEachWeight(q.triangle, q.bary,
                                 [&](int j, double w) { entries.emplace_back(i, j, share * w); });
  }
  e_.resize(nt, ns);
  e_.setFromTriplets(entries.begin(), entries.end());  // sums a node reached twice (corner and centre)
  e_.makeCompressed();
}

void PointwiseEvaluation::apply(const double* us, double* ut, int components) const {
  const int* outer = e_.outerIndexPtr();
  const int* inner = e_.innerIndexPtr();
  const double* value = e_.valuePtr();
  const int nt = int(e_.rows());
  if (components == 1) {
    for (int i = 0; i < nt; ++i) {
      double s = 0.0;
      for (int k = outer[i]; k < outer[i + 1]; ++k) s += value[k] * us[inner[k]];
      ut[i] = s;
    }
    return;
  }
  for (int i = 0; i < nt; ++i) {
    double s0 = 0.0, s1 = 0.0, s2 = 0.0;
    for (int k = outer[i]; k < outer[i + 1]; ++k) {
      const double* u = us + 3 * std::size_t(inner[k]);
      s0 += value[k] * u[0];
      s1 += value[k] * u[1];
      s2 += value[k] * u[2];
    }
    ut[3 * std::size_t(i)] = s0;
    ut[3 * std::size_t(i) + 1] = s1;
    ut[3 * std::size_t(i) + 2] = s2;
  }
}

}  // namespace fsi::coupling
