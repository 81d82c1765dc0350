#pragma once
// SurfaceSearch: closest point on an interface surface. The faces are fan-triangulated (FanTriangulation) and
// the triangles' bounding boxes put in a bounding-volume hierarchy, so a query returns the true closest
// triangle (box-distance pruning), not merely the one with the nearest centroid, in O(log N) typical time.

#include <array>
#include <limits>
#include <vector>

#include "coupling/interface/InterfaceMesh.hpp"

namespace fsi::coupling {

/// The piecewise-linear surface and field space of an InterfaceMesh. A triangle face stays one triangle; a
/// polygon with n ≥ 4 vertices becomes n triangles (centre, v_k, v_k+1) around its vertex average, and the
/// value at that centre is the average of the face's vertex values. Linear fields are thus reproduced
/// exactly on every face, and the space is continuous across faces (edges keep their two end nodes).
///
/// Fan corners are numbered: c < numPoints is mesh point c; numPoints + f is the centre of face f.
struct FanTriangulation {
  explicit FanTriangulation(const InterfaceMesh& mesh);

  int numPoints = 0;
  std::vector<std::array<int, 3>> triangles;   ///< corner ids; a polygon's centre is always corner 0
  std::vector<int> triangleFace;               ///< owning face of each triangle
  std::vector<std::array<double, 3>> corners;  ///< corner positions: the points, then every face's centre
  std::vector<int> faceOffsets, faceNodes;     ///< copy of the mesh's faces (a centre's nodes)

  int numTriangles() const { return int(triangles.size()); }

  /// Calls fn(node, weight) for every nodal shape function that is non-zero at barycentric point `bary` of
  /// triangle t (a node can be reported twice, through an edge corner and through the centre).
  template <class Fn>
  void forEachWeight(int t, const std::array<double, 3>& bary, Fn&& fn) const {
    const std::array<int, 3>& c = triangles[std::size_t(t)];
    for (int k = 0; k < 3; ++k) {
      if (bary[std::size_t(k)] == 0.0) continue;
      if (c[std::size_t(k)] < numPoints) {
        fn(c[std::size_t(k)], bary[std::size_t(k)]);
      } else {
        const int f = c[std::size_t(k)] - numPoints;
        const int begin = faceOffsets[std::size_t(f)], end = faceOffsets[std::size_t(f) + 1];
        const double w = bary[std::size_t(k)] / double(end - begin);
        for (int i = begin; i < end; ++i) fn(faceNodes[std::size_t(i)], w);
      }
    }
  }

  /// The discrete field with nodal values `values` (stride `components`, component `component`) at a point.
  double interpolate(int t, const std::array<double, 3>& bary, const double* values, int components = 1,
                     int component = 0) const;
  /// Position of barycentric point `bary` of triangle t.
  std::array<double, 3> position(int t, const std::array<double, 3>& bary) const;
  /// Area of triangle t.
  double area(int t) const;
};

/// Cosine below which two faces count as at right angles (neither facing nor opposing each other) in
/// SurfaceSearch::closestFacing and the projection's side rule: far above round-off, far below any real
/// angle between a skin and the mesh that follows it.
inline constexpr double kPerpendicular = 1e-9;

/// Result of a closest-point query.
struct SurfacePoint {
  int face = -1;                  ///< source face containing the closest point
  int triangle = -1;              ///< fan triangle containing it
  std::array<double, 3> bary{};   ///< its barycentric coordinates in that triangle
  std::array<double, 3> point{};  ///< its position
  double distance = std::numeric_limits<double>::infinity();
  bool mapped = false;  ///< distance ≤ the search's tolerance
};

class SurfaceSearch {
 public:
  /// Builds the hierarchy on `mesh` (O(N log N)); `tolerance` is the absolute distance beyond which a query
  /// is reported unmapped. Throws fsi::InputError for a face with fewer than 3 vertices or a bad index.
  explicit SurfaceSearch(const InterfaceMesh& mesh,
                         double tolerance = std::numeric_limits<double>::infinity());

  /// The closest point of the surface to x, always found (also when beyond the tolerance, then with
  /// mapped = false). `hint` is a triangle expected to be close (e.g. the previous query's): it only
  /// tightens the initial bound, the result does not depend on it.
  SurfacePoint closest(const std::array<double, 3>& x, int hint = -1) const;
  /// The closest point among the triangles that face the way of `facing` (normal · facing > 0, the normal
  /// by the face's vertex order, cosine above kPerpendicular): the point on the same side of a thin closed
  /// body (a trailing-edge wedge, whose two skins are closer to each other than to a non-matching mesh of the
  /// same skin). When no triangle faces that way, face = triangle = -1, distance = ∞ and mapped = false.
  SurfacePoint closestFacing(const std::array<double, 3>& x, const std::array<double, 3>& facing,
                             int hint = -1) const;
  /// Every closest point of x that is as close as `best` (closest(x)'s result) to round-off, one per distinct
  /// position: more than one where x lies on a symmetry plane of the surface, e.g. above a valley whose two
  /// flanks mirror each other, and `best` alone would take one side. Positions closer than round-off to each
  /// other (x over a shared edge or corner) count once. Always holds `best` first.
  std::vector<SurfacePoint> equallyClose(const std::array<double, 3>& x, const SurfacePoint& best) const;
  /// The (unnormalised, area-weighted) normal of fan triangle t, by its corner order.
  std::array<double, 3> normal(int t) const;

  const FanTriangulation& fan() const { return fan_; }
  double tolerance() const { return tolerance_; }

 private:
  struct BoxNode {
    std::array<double, 3> lo, hi;
    int first;  ///< leaf: first slot in order_; inner: index of the left child (the right one follows)
    int count;  ///< leaf: number of triangles; inner: 0
  };
  void build(int self, int begin, int end, const std::vector<std::array<double, 3>>& centroids);
  // Exact squared distance from x to slot s (triangle order_[s]); fills the barycentric coordinates.
  double distance2(int slot, const std::array<double, 3>& x, std::array<double, 3>& bary) const;
  std::array<double, 3> slotNormal(int slot) const;
  // The search of closest() over the slots `accept` lets through.
  template <class Accept>
  SurfacePoint search(const std::array<double, 3>& x, int hint, Accept&& accept) const;

  FanTriangulation fan_;
  double tolerance_;
  std::vector<BoxNode> nodes_;
  std::vector<int> order_;                       ///< triangles in leaf order
  std::vector<int> slotOf_;                      ///< inverse of order_
  std::vector<std::array<double, 9>> vertices_;  ///< triangle vertices in leaf order (cache locality)
};

}  // namespace fsi::coupling
