#pragma once
// FieldView: a non-owning view of one output field, what the element kinds fill (ElementKind::addFields) and
// the results writer (io/ResultsWriter) writes; CellSet: the cells one element kind writes its fields on
// (ElementKind::outputCells). Data only, so that the kinds need not know the writer.

#include <cstddef>
#include <string>
#include <vector>

namespace fsi::structure {

/// Non-owning view of one output field. Symmetric tensors (6 components) use the order xx yy zz xy yz xz,
/// which ParaView's Xdmf3 readers pass through unchanged and label XX YY ZZ XY YZ XZ (its legacy "XDMF
/// Reader" would assume xx xy xz yy yz zz instead; the datasets carry a component_order attribute).
struct FieldView {
  /// Node, or the cells of one cell set: Triangle and Line name the sets "Triangle" and "Line" (the
  /// membranes' and the cables'), Cell the set named by `cells` (any other kind's, e.g. "Bar").
  enum class Center { Node, Triangle, Line, Cell };
  static constexpr std::size_t kUnknownSize = static_cast<std::size_t>(-1);

  std::string name;
  Center center = Center::Node;
  int components = 1;            ///< 1 (scalar), 3 (vector) or 6 (symmetric tensor)
  const double* data = nullptr;  ///< count(center) * components values, row-major
  /// Number of doubles behind data, if the caller knows it; writeStep then checks it against the mesh.
  std::size_t size = kUnknownSize;
  std::string cells = {};  ///< the cell set's center name, for Center::Cell

  /// The name of the field's center: "Node" or its cell set's (the dataset attribute `center`).
  std::string centerName() const {
    switch (center) {
      case Center::Node:
        return "Node";
      case Center::Triangle:
        return "Triangle";
      case Center::Line:
        return "Line";
      case Center::Cell:
        break;
    }
    return cells;
  }
};

/// The cells of one element kind in a results file: its connectivity (model node indices) in
/// /mesh/<dataset> and, when it has cells, one XDMF grid `grid` of topology `topology` carrying the node
/// fields and the fields whose centerName() is `center`.
struct CellSet {
  std::string grid;      ///< XDMF grid name ("membranes", "cables", "bars")
  std::string dataset;   ///< HDF5 dataset under /mesh ("triangles", "lines", "bars")
  std::string center;    ///< the center name of its fields ("Triangle", "Line", "Bar")
  std::string topology;  ///< XDMF TopologyType ("Triangle", "Polyline")
  int nodesPerCell = 0;
  std::vector<int> conn;  ///< nodesPerCell node indices per cell
  std::size_t cells() const { return nodesPerCell > 0 ? conn.size() / std::size_t(nodesPerCell) : 0; }
};

}  // namespace fsi::structure
