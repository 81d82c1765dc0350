#pragma once
// The declared scene schema: every key of a schema section with its type, unit, default, valid range or
// choices and a one-line description, in one table per section, next to the reader of that section (the
// materials' in MaterialTypes.cpp, the parafoil's in parafoil/ParafoilScene.cpp, the run controls' in
// ReadControls.cpp, the probes' in scene/probes/). A section's reader reads through a SchemaMap, so the type
// and range checks, the defaults and the error messages (located at file:line:col and key path by YamlMap)
// come from the entry; the valid keys of YamlMap::finish are the section's key names.
//
// sceneSchema() gathers every section from the registries that hold them (material types, generator kinds,
// probe readers) in the order of docs/SCENES.md; schemaMarkdown() is the key reference there, between the
// markers `<!-- scene-schema:begin -->` and `<!-- scene-schema:end -->` (`fsi scene-keys --markdown` prints
// it; tests/unit/test_scene_schema.cpp fails when docs and schema differ, schemaDocsProblems()).

#include <array>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "structure/model/SchemaKey.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure {

/// Reads one mapping of the scene through its schema section: every value is checked against its key's
/// type and range (the message from the entry, located by YamlMap); an absent key takes its default.
/// Reading a key the section does not declare is a programming error (std::logic_error).
class SchemaMap {
 public:
  /// Reads `map` (which must outlive this; reads through either are one record of used keys).
  SchemaMap(const YamlMap& map, const SchemaSection& section) : map_(map), section_(section) {}

  bool has(const std::string& key) const;
  double number(const std::string& key) const;  ///< given, else the default; a missing required key fails
  long integer(const std::string& key) const;
  bool boolean(const std::string& key) const;
  std::string string(const std::string& key) const;  ///< String or Choice (one of the choices)
  std::vector<double> numbers(const std::string& key) const;
  std::array<double, 3> vec3(const std::string& key) const;
  /// The value if given, else nullopt (for keys whose absence means "unset").
  std::optional<double> optionalNumber(const std::string& key) const;
  /// Throws unless every key of the mapping was read; valid keys are the section's.
  void finish() const { map_.finish(section_.names()); }

  const YamlMap& map() const { return map_; }
  const SchemaSection& section() const { return section_; }

 private:
  const SceneKey& declared(const std::string& key, std::initializer_list<KeyType> types) const;
  void checkRange(const SceneKey& k, double v, const std::string& shown) const;
  const YamlMap& map_;
  const SchemaSection& section_;
};

/// The top level's sections and a mesh entry's keys (SceneSections.cpp).
const SchemaSection& topLevelSchema();
const SchemaSection& meshEntrySchema();

/// Every schema section, in the order of docs/SCENES.md's key reference.
std::vector<const SchemaSection*> sceneSchema();

/// The key reference: one table per section (what docs/SCENES.md holds between its markers).
std::string schemaMarkdown();

/// What differs between the key reference in `doc` (the text of docs/SCENES.md) and the schema: a missing
/// marker, every schema key the docs lack, every documented key the schema lacks, every row that differs.
/// Empty when they agree.
std::vector<std::string> schemaDocsProblems(const std::string& doc);

}  // namespace fsi::structure
