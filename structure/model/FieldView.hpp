#pragma once
// FieldView: a non-owning view of one output field, what the element kinds fill (ElementKind::addFields) and
// the results writer (io/ResultsWriter) writes. Data only, so that the kinds need not know the writer.

#include <cstddef>
#include <string>

namespace fsi::structure {

/// Non-owning view of one output field. Symmetric tensors (6 components) use the order xx yy zz xy yz xz,
/// which ParaView's Xdmf3 readers pass through unchanged and label XX YY ZZ XY YZ XZ (its legacy "XDMF
/// Reader" would assume xx xy xz yy yz zz instead; the datasets carry a component_order attribute).
struct FieldView {
  enum class Center { Node, Triangle, Line };
  static constexpr std::size_t kUnknownSize = static_cast<std::size_t>(-1);

  std::string name;
  Center center = Center::Node;
  int components = 1;            ///< 1 (scalar), 3 (vector) or 6 (symmetric tensor)
  const double* data = nullptr;  ///< count(center) * components values, row-major
  /// Number of doubles behind data, if the caller knows it; writeStep then checks it against the mesh.
  std::size_t size = kUnknownSize;
};

}  // namespace fsi::structure
