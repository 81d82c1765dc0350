#pragma once
// Built-in parametric meshes for scenes and tests. Every generator returns a MeshData with 1-based point,
// triangle and line tags (1..n in index order) and triangles counter-clockwise about the stated normal.
// Invalid parameters throw fsi::InputError naming the generator and the parameter.

#include <array>
#include <string>
#include <vector>

#include "structure/model/MeshData.hpp"

namespace fsi::structure {

using Point3 = std::array<double, 3>;

/// Flat rectangle in the plane z = center.z, normal +z.
/// pattern: "ruled" (every square cut from (i,j) to (i+1,j+1)), "alternating" (diagonal direction
/// alternates like a checkerboard) or "cross" (extra node at every square's centre, 4 triangles per square).
/// Grid node (i,j) has index j*(nx+1)+i; cross centres follow, square (i,j) at (nx+1)(ny+1)+j*nx+i.
/// Groups: nodes "boundary", "xmin", "xmax", "ymin", "ymax"; triangles "all".
struct RectangleParams {
  std::array<double, 2> size{1.0, 1.0};  ///< Lx, Ly [m]
  std::array<int, 2> divisions{1, 1};    ///< nx, ny squares
  Point3 center{0.0, 0.0, 0.0};
  std::string pattern = "ruled";
};
MeshData rectangle(const RectangleParams& params, const std::string& name = "rectangle");

/// Flat disc in the plane z = center.z, normal +z: a centre node (index 0) and rings k = 1..n of 6k nodes
/// at radius kR/n, equally spaced in angle starting on +x (hexagonal-ring construction, 6n² triangles).
/// The triangulated area is that of the regular 6n-gon inscribed in the circle.
/// Groups: nodes "center", "rim"; triangles "all".
struct DiscParams {
  double radius = 1.0;
  int rings = 1;
  Point3 center{0.0, 0.0, 0.0};
};
MeshData disc(const DiscParams& params, const std::string& name = "disc");

/// One eighth of the sphere of radius r about the origin (x, y, z >= 0): the flat triangle (r,0,0),
/// (0,r,0), (0,0,r) cut into n² triangles, every node projected radially onto the sphere. Normal outward.
/// Groups: nodes "x0", "y0", "z0" (nodes on those planes, coordinate exactly 0); triangles "all".
struct SphereOctantParams {
  double radius = 1.0;
  int divisions = 1;
};
MeshData sphereOctant(const SphereOctantParams& params, const std::string& name = "sphereOctant");

/// Polyline p0..pm (m >= 1 segments) cut into lines: `divisions` holds one count for every segment or one
/// per segment. Node 0 is p0, the nodes follow the path. Groups: nodes "start", "end"; lines "all".
struct CableChainParams {
  std::vector<Point3> points;
  std::vector<int> divisions{1};
};
MeshData cableChain(const CableChainParams& params, const std::string& name = "cableChain");

/// Strip swept from a polyline path (as in cableChain) by the width vector w: it spans path + s·w,
/// s in [0, 1], with `across` divisions. Normal = (path direction) × w, segment by segment.
/// pattern: "ruled" or "alternating". Node (i along the path, j across) has index j*N+i, N path nodes.
/// Groups: nodes "start" (across the first path point), "end" (across the last), "side0" (the path,
/// s = 0), "side1" (s = 1); triangles "all".
struct StripParams {
  std::vector<Point3> path;
  std::vector<int> divisions{1};  ///< along the path: one for all segments or one per segment
  Point3 width{0.0, 1.0, 0.0};    ///< w [m]
  int across = 1;
  std::string pattern = "ruled";
};
MeshData strip(const StripParams& params, const std::string& name = "strip");

/// Two flat faces in the plane z = center.z joined at their rim: the top face with normal +z, the bottom
/// face with normal -z. Rim nodes are shared; interior nodes are distinct but coincident in space.
/// shape: "rectangle" (uses `rectangle`) or "disc" (uses `disc`). Top face nodes come first, in the order
/// of the single-face generator, then the bottom's interior nodes in the same order.
/// Groups: nodes "rim", "top" (incl. rim), "bottom" (incl. rim), "top_center", "bottom_center" (only when
/// a face has a node exactly at its centre: disc always; rectangle with even nx and ny, or pattern "cross"
/// with odd nx and ny); triangles "top", "bottom", "all".
struct PillowParams {
  std::string shape = "rectangle";
  RectangleParams rectangle;
  DiscParams disc;
};
MeshData pillow(const PillowParams& params, const std::string& name = "pillow");

}  // namespace fsi::structure
