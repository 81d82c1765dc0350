#pragma once
// InterfaceMesh: one side's view of the fluid–structure interface in the UNDEFORMED configuration: points and
// polygonal faces (triangles from the structure, general polygons from OpenFOAM), counter-clockwise about
// the outward normal. Projections between two such meshes are set up once on these geometries.

#include <array>
#include <initializer_list>
#include <string>
#include <vector>

namespace fsi::coupling {

struct InterfaceMesh {
  std::string name;
  std::vector<std::array<double, 3>> points;
  std::vector<int> faceOffsets{0};  ///< face f has vertices faceNodes[faceOffsets[f] .. faceOffsets[f+1])
  std::vector<int> faceNodes;

  int numPoints() const { return int(points.size()); }
  int numFaces() const { return int(faceOffsets.size()) - 1; }
  int faceSize(int f) const { return faceOffsets[f + 1] - faceOffsets[f]; }
  const int* face(int f) const { return faceNodes.data() + faceOffsets[f]; }
  void addFace(std::initializer_list<int> nodes) {
    faceNodes.insert(faceNodes.end(), nodes);
    faceOffsets.push_back(int(faceNodes.size()));
  }
  void addFace(const std::vector<int>& nodes) {
    faceNodes.insert(faceNodes.end(), nodes.begin(), nodes.end());
    faceOffsets.push_back(int(faceNodes.size()));
  }

  /// Vertex average of face f: the extra fan vertex of polygon faces (see FanTriangulation).
  std::array<double, 3> faceCentroid(int f) const;
  /// Area of face f, a planar or slightly warped polygon: the fan of triangles about its vertex average.
  double faceArea(int f) const;
  /// Lumped area of each point, Σ over its faces of A_f / n_f (0 for a point on no face).
  std::vector<double> pointAreas() const;
  /// Mean length of the face edges (a length scale for search tolerances); 0 without faces.
  double meanEdgeLength() const;
};

}  // namespace fsi::coupling
