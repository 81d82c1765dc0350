#include "coupling/effects/PointCloudInterpolation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fsi::coupling {

PointCloudSearch::PointCloudSearch(const std::vector<std::array<double, 3>>& points) : points_(points) {
  std::array<double, 3> hi{};
  lo_ = hi = points.empty() ? std::array<double, 3>{} : points[0];
  for (const auto& p : points)
    for (int k = 0; k < 3; ++k) lo_[k] = std::min(lo_[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  double diag = 0;
  for (int k = 0; k < 3; ++k) diag += (hi[k] - lo_[k]) * (hi[k] - lo_[k]);
  diag = std::sqrt(diag);
  const double n = double(std::max<std::size_t>(points.size(), 1));
  // Points on a surface: about one per cell for a cell of diag/√N; fewer cells than ~4N+64 in any case.
  cell_ = diag > 0 ? diag / std::sqrt(n) : 1.0;
  for (;;) {
    double cells = 1;
    for (int k = 0; k < 3; ++k) cells *= std::floor((hi[k] - lo_[k]) / cell_) + 1;
    if (cells <= 4 * n + 64) break;
    cell_ *= 1.25;
  }
  long total = 1;
  for (int k = 0; k < 3; ++k) total *= dims_[k] = long(std::floor((hi[k] - lo_[k]) / cell_)) + 1;
  start_.assign(std::size_t(total) + 1, 0);
  std::vector<long> cellOf(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    long c = 0;
    for (int k = 2; k >= 0; --k)
      c = c * dims_[k] + std::min(dims_[k] - 1, long(std::floor((points[i][k] - lo_[k]) / cell_)));
    cellOf[i] = c;
    ++start_[std::size_t(c) + 1];
  }
  for (std::size_t c = 0; c + 1 < start_.size(); ++c) start_[c + 1] += start_[c];
  index_.resize(points.size());
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < points.size(); ++i)
    index_[std::size_t(fill[std::size_t(cellOf[i])]++)] = int(i);
}

void PointCloudSearch::nearest(const std::array<double, 3>& x, int k, double radius,
                               std::vector<std::pair<double, int>>& out) const {
  out.clear();
  long c[3];
  long r0 = 0, rEnd = 0;  // first shell that meets the grid, last shell that still does
  for (int a = 0; a < 3; ++a) {
    const double f = std::floor((x[a] - lo_[a]) / cell_);
    c[a] = long(std::clamp(f, -1e15, 1e15));
    r0 = std::max(r0, c[a] < 0 ? -c[a] : (c[a] >= dims_[a] ? c[a] - dims_[a] + 1 : 0));
    rEnd = std::max(rEnd, std::max(c[a], dims_[a] - 1 - c[a]));
  }
  auto kth = [&] {
    return out.size() < std::size_t(k) ? std::numeric_limits<double>::infinity() : out.back().first;
  };
  for (long r = r0; r <= rEnd; ++r) {
    // Points in shells beyond r are at least r·cell away: stop once they cannot enter the list.
    if (double(r - 1) * cell_ > std::min(radius, kth())) break;
    for (long i = std::max(c[0] - r, 0L); i <= std::min(c[0] + r, dims_[0] - 1); ++i)
      for (long j = std::max(c[1] - r, 0L); j <= std::min(c[1] + r, dims_[1] - 1); ++j)
        for (long m = std::max(c[2] - r, 0L); m <= std::min(c[2] + r, dims_[2] - 1); ++m) {
          if (std::max({std::labs(i - c[0]), std::labs(j - c[1]), std::labs(m - c[2])}) != r) continue;
          const long cell = (m * dims_[1] + j) * dims_[0] + i;
          for (int s = start_[std::size_t(cell)]; s < start_[std::size_t(cell) + 1]; ++s) {
            const auto& p = points_[std::size_t(index_[std::size_t(s)])];
            const double d = std::sqrt((p[0] - x[0]) * (p[0] - x[0]) + (p[1] - x[1]) * (p[1] - x[1]) +
                                       (p[2] - x[2]) * (p[2] - x[2]));
            if (d > radius || d >= kth()) continue;
            const std::pair<double, int> e{d, index_[std::size_t(s)]};
            out.insert(std::upper_bound(out.begin(), out.end(), e), e);
            if (out.size() > std::size_t(k)) out.pop_back();
          }
        }
  }
}

CloudInterpolation interpolateCloud(const std::vector<std::array<double, 3>>& cloud,
                                    const std::vector<double>& values,
                                    const std::vector<std::array<double, 3>>& queries, int neighbours,
                                    double tolerance) {
  const PointCloudSearch search(cloud);
  CloudInterpolation r;
  r.values.assign(queries.size(), 0.0);
  std::vector<std::pair<double, int>> near;
  for (std::size_t q = 0; q < queries.size(); ++q) {
    search.nearest(queries[q], neighbours, tolerance, near);
    if (near.empty()) {
      search.nearest(queries[q], 1, std::numeric_limits<double>::infinity(), near);
      r.firstFailed = int(q);
      r.failedDistance = near.empty() ? std::numeric_limits<double>::infinity() : near[0].first;
      return r;
    }
    // A cloud point at the query (to round-off of the cloud's size) is the value itself.
    if (near[0].first <=
        1e-12 * (1.0 + std::abs(queries[q][0]) + std::abs(queries[q][1]) + std::abs(queries[q][2]))) {
      r.values[q] = values[std::size_t(near[0].second)];
      continue;
    }
    double sw = 0, sv = 0;
    for (const auto& [d, i] : near) {
      const double w = 1.0 / (d * d);
      sw += w;
      sv += w * values[std::size_t(i)];
    }
    r.values[q] = sv / sw;
  }
  return r;
}

}  // namespace fsi::coupling
