// The scene schema as docs: the key reference of docs/SCENES.md (schemaMarkdown) and its check
// (schemaDocsProblems).
#include <fmt/format.h>

#include <map>
#include <sstream>

#include "structure/scene/SceneSchema.hpp"

namespace fsi::structure {

namespace {

const std::string kBegin = "<!-- scene-schema:begin -->\n";
const std::string kEnd = "<!-- scene-schema:end -->";

std::string cell(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out.empty() ? "" : out;
}

std::string row(const SceneKey& k) {
  return fmt::format("| `{}` | {} | {} | {} | {} | {} |", k.name, toString(k.type), cell(k.defaultText()),
                     cell(k.rangeText()), cell(k.unit), cell(k.description));
}

// (section path, key) -> its table row, of a key reference's text.
using Rows = std::map<std::pair<std::string, std::string>, std::string>;

Rows rowsOf(const std::string& block) {
  Rows rows;
  std::istringstream is(block);
  std::string line, section;
  while (std::getline(is, line)) {
    if (line.rfind("### `", 0) == 0) {
      const auto end = line.find('`', 5);
      section = line.substr(5, end == std::string::npos ? std::string::npos : end - 5);
    } else if (line.rfind("| `", 0) == 0) {
      const auto end = line.find('`', 3);
      rows[{section, line.substr(3, end == std::string::npos ? std::string::npos : end - 3)}] = line;
    }
  }
  return rows;
}

}  // namespace

std::string schemaMarkdown() {
  std::string md;
  for (const SchemaSection* s : sceneSchema()) {
    md += fmt::format("### `{}`\n\n{}\n\n", s->path, s->description);
    md += "| key | type | default | range | unit | description |\n|---|---|---|---|---|---|\n";
    for (const SceneKey& k : s->keys) md += row(k) + "\n";
    md += "\n";
  }
  return md;
}

std::vector<std::string> schemaDocsProblems(const std::string& doc) {
  const auto a = doc.find(kBegin), b = doc.find(kEnd);
  if (a == std::string::npos || b == std::string::npos || b < a)
    return {fmt::format("docs/SCENES.md has no key reference between '{}' and '{}'",
                        kBegin.substr(0, kBegin.size() - 1), kEnd)};
  const std::string block = doc.substr(a + kBegin.size(), b - a - kBegin.size());
  const std::string expected = schemaMarkdown();
  const Rows docs = rowsOf(block), schema = rowsOf(expected);
  std::vector<std::string> problems;
  for (const auto& [where, line] : schema) {
    const auto it = docs.find(where);
    if (it == docs.end())
      problems.push_back(fmt::format("section '{}': key '{}' is in the schema but not in docs/SCENES.md",
                                     where.first, where.second));
    else if (it->second != line)
      problems.push_back(fmt::format("section '{}': key '{}': docs/SCENES.md has\n  {}\nthe schema\n  {}",
                                     where.first, where.second, it->second, line));
  }
  for (const auto& [where, line] : docs)
    if (!schema.count(where))
      problems.push_back(fmt::format("section '{}': key '{}' is in docs/SCENES.md but not in the schema",
                                     where.first, where.second));
  if (problems.empty() && block != expected)
    problems.push_back(
        "docs/SCENES.md's key reference differs from the schema in its headings or descriptions");
  if (!problems.empty())
    problems.push_back("regenerate it: fsi scene-keys --markdown (between the scene-schema markers)");
  return problems;
}

}  // namespace fsi::structure
