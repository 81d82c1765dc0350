#pragma once
// MeshData: one mesh as read from a file or built by a generator, before it joins the Model.
// Plain containers only; the Model turns these into renumbered structure-of-arrays data.

#include <array>
#include <map>
#include <string>
#include <vector>

namespace fsi::structure {

struct MeshData {
  std::string name;                           ///< mesh name from the scene
  std::vector<std::array<double, 3>> points;  ///< reference coordinates [m]
  std::vector<long> pointTags;                ///< user-facing node ids (Gmsh tags; 1-based for generators)
  std::vector<std::array<int, 3>> triangles;  ///< membrane triangles, indices into points (CCW = normal)
  std::vector<std::array<int, 2>> lines;      ///< cables, indices into points
  std::vector<long> triangleTags;             ///< user-facing element ids, one per triangle
  std::vector<long> lineTags;                 ///< user-facing element ids, one per line
  /// Rest lengths of the lines [m] where they differ from the reference distance of their end points (a line
  /// rigged with slack); empty, or 0 for a line: the reference distance. Only generators set them (a Gmsh
  /// file has no place for them).
  std::vector<double> lineRestLength;
  /// Where the nodes start when they do not start at their reference coordinates (a canopy packed or pulled
  /// out to line stretch, its stress-free shape the constructed one); empty: at `points`. Only generators set
  /// them; a run starts there at rest, a relaxation too.
  std::vector<std::array<double, 3>> startPoints;
  std::map<std::string, std::vector<int>> nodeGroups;      ///< named node groups (indices into points)
  std::map<std::string, std::vector<int>> triangleGroups;  ///< named triangle groups (indices into triangles)
  std::map<std::string, std::vector<int>> lineGroups;      ///< named line groups (indices into lines)
};

}  // namespace fsi::structure
