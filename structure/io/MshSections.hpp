#pragma once
// Internal to MshReader: the section readers of MSH 2 (MshSections2.cpp) and MSH 4.1 (MshSections4.cpp) and
// the node-tag index they share. Each reader starts after its "$Section" line and consumes "$EndSection".

#include <unordered_map>
#include <vector>

#include "structure/io/MshInput.hpp"
#include "structure/io/MshReader.hpp"

namespace fsi::structure::msh {

/// Node tag -> index into MshContent::nodeTags. Tags below a limit set from the node count (which the file
/// size bounds) go into a table, any others into a hash map, so a huge tag cannot make it allocate.
class NodeIndex {
 public:
  void reserve(long long numNodes, long long maxTag);
  /// False if `tag` is already there.
  bool add(long long tag, int index);
  /// -1 if absent.
  int find(long long tag) const {
    if (tag >= 0 && static_cast<unsigned long long>(tag) < dense_.size()) return dense_[std::size_t(tag)];
    const auto it = sparse_.find(tag);
    return it == sparse_.end() ? -1 : it->second;
  }

 private:
  std::vector<int> dense_;
  std::unordered_map<long long, int> sparse_;
};

/// Dimension of a supported element type, or -1.
int elementDimension(int type);
/// Fails at the current position: `type` is not one the project reads (names it and the supported ones).
[[noreturn]] void failUnsupportedType(const MshInput& in, long long elementTag, long long type);

void readPhysicalNames(MshInput& in, MshContent& mesh);

/// $Nodes, or $ParametricNodes (each node also gives its entity and parametric coordinates).
void readNodes2(MshInput& in, MshContent& mesh, NodeIndex& index, bool parametric);
void readElements2(MshInput& in, MshContent& mesh, const NodeIndex& index);

void readEntities4(MshInput& in, MshContent& mesh);
void readNodes4(MshInput& in, MshContent& mesh, NodeIndex& index);
void readElements4(MshInput& in, MshContent& mesh, const NodeIndex& index);

}  // namespace fsi::structure::msh
