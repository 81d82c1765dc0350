#pragma once
// Interpolation from a point cloud without connectivity (the CSV form of `pressure_field`). A cloud has no
// areas, so no conservative projection exists for it; the value at a point is the CONSISTENT inverse-distance
// average of its k nearest cloud points, weights 1/d² (the cloud point itself where it coincides), using only
// cloud points within `tolerance`. A query with no cloud point within the tolerance is reported, never
// extrapolated. Error O(h) for a smooth field sampled at spacing h.

#include <array>
#include <vector>

namespace fsi::coupling {

/// k-nearest search over a fixed point set: a uniform grid of about one point per cell (sized for points on
/// a surface), searched in growing shells around the query.
class PointCloudSearch {
 public:
  /// Keeps a reference to `points`: they must outlive the search.
  explicit PointCloudSearch(const std::vector<std::array<double, 3>>& points);
  /// Up to k nearest points no farther than `radius`, as (distance, index), nearest first.
  void nearest(const std::array<double, 3>& x, int k, double radius,
               std::vector<std::pair<double, int>>& out) const;

 private:
  const std::vector<std::array<double, 3>>& points_;
  std::array<double, 3> lo_{};
  double cell_ = 1.0;
  std::array<long, 3> dims_{1, 1, 1};
  std::vector<int> start_, index_;  ///< CSR: points of cell c are index_[start_[c] .. start_[c+1])
};

struct CloudInterpolation {
  std::vector<double> values;  ///< one per query
  int firstFailed = -1;        ///< first query with no cloud point within the tolerance (−1: none)
  double failedDistance = 0;   ///< its distance to the nearest cloud point
};

/// The inverse-distance values of `values` (one per cloud point) at every query point.
CloudInterpolation interpolateCloud(const std::vector<std::array<double, 3>>& cloud,
                                    const std::vector<double>& values,
                                    const std::vector<std::array<double, 3>>& queries, int neighbours,
                                    double tolerance);

}  // namespace fsi::coupling
