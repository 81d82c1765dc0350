#pragma once
// Resolves the scene's node and triangle selectors (set names, 'mesh/group', plane, box, nearest, ids and
// lists of them) against the built Model. Every error is located at the selector in the scene file.

#include <yaml-cpp/yaml.h>

#include <map>
#include <string>
#include <vector>

#include "structure/model/Model.hpp"

namespace fsi::structure {

class SetResolver {
 public:
  SetResolver(const Model& model, const std::string& file) : model_(model), file_(file) {}

  const Model& model() const { return model_; }

  /// Declares the named set `name` (`sets:` entry) with its selector and key path.
  void define(const std::string& name, YAML::Node sel, const std::string& path);

  /// The sorted, distinct model nodes `sel` selects; an empty selection is an error.
  std::vector<int> nodes(const YAML::Node& sel, const std::string& path) const;

  /// Resolves the set `name` as a node selection (through the memo and the cycle check).
  void resolveNamed(const std::string& name) const;

  /// The sorted, distinct membrane elements `sel` selects; an empty selection is an error.
  std::vector<int> triangles(const YAML::Node& sel, const std::string& path) const;

  /// The sorted, distinct cable elements `sel` selects: 'mesh' (all its lines), 'mesh/group' (a line group)
  /// or a list of them; an empty selection is an error.
  std::vector<int> lines(const YAML::Node& sel, const std::string& path) const;

 private:
  struct Named {
    YAML::Node sel;
    std::string path;
  };
  using Memo = std::map<std::string, std::vector<int>>;

  static void sortUnique(std::vector<int>& v);
  static void append(std::vector<int>& out, const std::vector<int>& part, std::size_t entities);
  template <class Resolve>
  static std::vector<int> listUnion(const YAML::Node& list, const std::string& path, std::size_t entities,
                                    Resolve resolve);
  template <class Resolve>
  std::vector<int> namedSet(const std::string& name, const Named& set, const YAML::Node& at,
                            const std::string& path, Memo& memo, Resolve resolve) const;
  int meshIndex(const std::string& name, const YAML::Node& at, const std::string& path) const;
  std::vector<int> nodesByName(const std::string& s, const YAML::Node& at, const std::string& path) const;
  std::vector<int> trianglesByName(const std::string& s, const YAML::Node& at, const std::string& path) const;
  std::vector<int> nodesRaw(const YAML::Node& sel, const std::string& path) const;
  std::vector<int> trianglesRaw(const YAML::Node& sel, const std::string& path) const;
  std::vector<int> linesRaw(const YAML::Node& sel, const std::string& path) const;
  using Groups = std::map<std::string, std::vector<int>>;
  std::vector<int> meshElements(const std::string& s, const YAML::Node& at, const std::string& path,
                                const char* kind, Groups MeshData::*groups,
                                std::vector<int> MeshMap::*toModel) const;

  const Model& model_;
  std::string file_;
  std::map<std::string, Named> named_;
  mutable Memo nodeMemo_, triangleMemo_;
  mutable std::vector<std::string> resolving_;  // outermost first
};

}  // namespace fsi::structure

namespace fsi::structure {

class YamlMap;

/// Defines the `sets:` section of the top-level map `top` in `sets` and resolves every set once, used or
/// not, so that a typo in an unused set is still reported.
void defineSets(const YamlMap& top, const Model& model, SetResolver& sets);

}  // namespace fsi::structure
