#pragma once
// MshReader: reads a Gmsh MSH file (versions 2.0-2.2 and 4.1, ASCII or binary) into MshContent, the part of
// the file the project uses: nodes, the elements it can use (points, 2-node lines, 3-node triangles, 4-node
// quadrangles), the entities they belong to, physical groups and their names.
//
// Written for hostile input (the Gmsh library is not: bad counts, tags or headers crash it, and it executes
// .geo scripts): every count is checked against the bytes left before allocating, every tag and number is
// range-checked (overflow, nan, inf are errors), every node reference resolved. All problems are an
// fsi::InputError naming the file, the line (ASCII) or byte offset (binary), the section and what is wrong.
// Nothing in the file is ever executed: anything that is not an MSH file is refused.

#include <array>
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace fsi::structure {

/// Gmsh element type numbers the project reads.
enum MshElementType : int { kMshLine2 = 1, kMshTriangle3 = 2, kMshQuad4 = 3, kMshPoint = 15 };

struct MshContent {
  using DimTag = std::pair<int, int>;  ///< (entity dimension 0..3, entity tag)

  struct Element {
    long tag = 0;
    int type = 0;           ///< one of MshElementType
    DimTag entity{0, 0};    ///< the entity it belongs to (dimension = the type's dimension)
    std::size_t first = 0;  ///< its nodes: nodes[first], ... (1 to 4 of them, by type)
    std::size_t where = 0;  ///< line (ASCII) or byte offset (binary) of its record, for messages
  };

  std::string file;  ///< the path, for messages
  bool binary = false;
  std::vector<long> nodeTags;                     ///< in file order
  std::vector<std::array<double, 3>> nodeCoords;  ///< one per node tag
  std::vector<Element> elements;                  ///< in file order
  std::vector<int> elementNodes;                  ///< indices into nodeTags
  /// MSH 4: nodes the file classifies on a point entity (entity tag, index into nodeTags).
  std::vector<std::pair<int, int>> pointEntityNodes;
  /// Every entity the file mentions, with its physical group tags (> 0; none for most entities).
  std::map<DimTag, std::vector<int>> entities;
  std::map<DimTag, std::string> physicalNames;  ///< (dimension, physical tag) -> name

  /// "file:12" (ASCII) or "file, byte 345" (binary), for a `where` above.
  std::string where(std::size_t at) const;
};

/// Number of nodes of a supported element type.
int mshNodesPerElement(int type);
/// Gmsh's name of an element type ("Triangle 6"), or "unknown" for a number Gmsh does not define.
const char* mshElementTypeName(int type);

/// Reads `file`. Throws fsi::InputError (located) for a missing, unreadable or non-MSH file (a .geo
/// script is refused with the command that meshes it), an unsupported version, element type or layout,
/// and any inconsistency; never anything else (a file too large for memory is an InputError too).
MshContent readMshFile(const std::filesystem::path& file);

}  // namespace fsi::structure
