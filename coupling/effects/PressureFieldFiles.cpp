#include "coupling/effects/PressureFieldFiles.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "structure/model/Error.hpp"

namespace fsi::coupling {

namespace {

std::string readWhole(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw InputError(fmt::format("{}: no such file (or not a regular file)", file.string()));
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open", file.string()));
  std::stringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw InputError(fmt::format("{}: cannot read", file.string()));
  return ss.str();
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string trim(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

// A token as messages show it: bytes outside printable ASCII as \xNN, long ones cut (a binary or corrupted
// file must not put control characters or megabytes into a message).
std::string shown(const std::string& t) {
  std::string out;
  for (std::size_t i = 0; i < t.size() && i < 40; ++i) {
    const unsigned char c = static_cast<unsigned char>(t[i]);
    out += (c >= 32 && c < 127) ? std::string(1, char(c)) : fmt::format("\\x{:02X}", c);
  }
  return t.size() > 40 ? out + "..." : out;
}

// A finite number filling the whole token; false otherwise (nan, inf, trailing characters, overflow).
bool parseFinite(const std::string& t, double& v) {
  if (t.empty()) return false;
  errno = 0;
  char* end = nullptr;
  v = std::strtod(t.c_str(), &end);
  return end == t.c_str() + t.size() && errno != ERANGE && std::isfinite(v);
}

bool parseLong(const std::string& t, long& v) {
  if (t.empty()) return false;
  errno = 0;
  char* end = nullptr;
  v = std::strtol(t.c_str(), &end, 10);
  return end == t.c_str() + t.size() && errno != ERANGE;
}

// ---------------------------------------------------------------- CSV point cloud

std::vector<std::string> splitCommas(const std::string& line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t c = line.find(',', start);
    out.push_back(trim(line.substr(start, c == std::string::npos ? std::string::npos : c - start)));
    if (c == std::string::npos) break;
    start = c + 1;
  }
  return out;
}

}  // namespace

PointCloud readPointCloudCsv(const std::filesystem::path& file, const std::string& column) {
  std::string text = readWhole(file);
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);  // a UTF-8 byte-order mark (spreadsheet export)
  const std::string f = file.string();
  std::istringstream in(text);
  std::string line;
  long lineNo = 0;
  std::vector<std::string> header;
  long headerLine = 0;
  int col[4] = {-1, -1, -1, -1};  // x, y, z, field
  const std::string wanted[4] = {"x", "y", "z", lower(column)};
  PointCloud cloud;
  while (std::getline(in, line)) {
    ++lineNo;
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    const std::vector<std::string> fields = splitCommas(t);
    if (header.empty()) {
      header = fields;
      headerLine = lineNo;
      for (std::size_t i = 0; i < header.size(); ++i) {
        const std::string name = lower(header[i]);
        if (name.empty()) throw InputError(fmt::format("{}:{}: column {} has no name", f, lineNo, i + 1));
        for (std::size_t j = 0; j < i; ++j)
          if (lower(header[j]) == name)
            throw InputError(fmt::format("{}:{}: column '{}' given twice", f, lineNo, shown(header[i])));
        for (int k = 0; k < 4; ++k)
          if (name == wanted[k]) col[k] = int(i);
      }
      std::string missing;
      for (int k = 0; k < 4; ++k)
        if (col[k] < 0) missing += (missing.empty() ? "'" : ", '") + wanted[k] + "'";
      if (!missing.empty()) {
        std::string have;
        for (const auto& h : header) have += (have.empty() ? "" : ", ") + shown(h);
        throw InputError(fmt::format("{}:{}: the header has no column {} (columns: {}; needed: x, y, z, {})",
                                     f, lineNo, missing, have, column));
      }
      continue;
    }
    if (fields.size() != header.size())
      throw InputError(fmt::format("{}:{}: {} values, the header (line {}) has {} columns", f, lineNo,
                                   fields.size(), headerLine, header.size()));
    double v[4];
    for (int k = 0; k < 4; ++k)
      if (!parseFinite(fields[std::size_t(col[k])], v[k]))
        throw InputError(fmt::format("{}:{}: column '{}': '{}' is not a finite number", f, lineNo,
                                     shown(header[std::size_t(col[k])]), shown(fields[std::size_t(col[k])])));
    cloud.points.push_back({v[0], v[1], v[2]});
    cloud.values.push_back(v[3]);
  }
  if (header.empty())
    throw InputError(fmt::format("{}: empty file: no header line (x, y, z, {})", f, column));
  if (cloud.points.empty())
    throw InputError(fmt::format("{}:{}: no data rows after the header", f, headerLine));
  return cloud;
}

// ---------------------------------------------------------------- legacy VTK surface

namespace {

// Whitespace-separated tokens of the text with the line each starts on.
class Tokens {
 public:
  Tokens(const std::string& text, std::string file) : s_(text), file_(std::move(file)) {}

  // One whole line (the three header lines), without its end; false at the end of the text.
  bool line(std::string& out) {
    if (pos_ >= s_.size()) return false;
    const std::size_t e = s_.find('\n', pos_);
    out = s_.substr(pos_, e == std::string::npos ? std::string::npos : e - pos_);
    if (!out.empty() && out.back() == '\r') out.pop_back();
    pos_ = e == std::string::npos ? s_.size() : e + 1;
    if (e != std::string::npos) ++line_;
    return true;
  }
  bool next(std::string& tok) {
    skipSpace();
    if (pos_ >= s_.size()) return false;
    tokLine_ = line_;
    const std::size_t b = pos_;
    while (pos_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    tok = s_.substr(b, pos_ - b);
    return true;
  }
  // The next token without taking it; `onLine` is set to the line it starts on.
  std::string peek(long* onLine = nullptr) {
    const std::size_t p = pos_;
    const long l = line_, tl = tokLine_;
    std::string t;
    if (!next(t)) t.clear();
    if (onLine) *onLine = tokLine_;
    pos_ = p, line_ = l, tokLine_ = tl;
    return t;
  }
  std::string need(const std::string& what) {
    std::string t;
    if (!next(t)) fail(fmt::format("the file ends where {} was expected", what), line_);
    return t;
  }
  double number(const std::string& what) {
    const std::string t = need(what);
    double v = 0;
    if (!parseFinite(t, v)) fail(fmt::format("{}: '{}' is not a finite number", what, shown(t)));
    return v;
  }
  long integer(const std::string& what, long lo, long hi) {
    const std::string t = need(what);
    long v = 0;
    if (!parseLong(t, v) || v < lo || v > hi)
      fail(fmt::format("{}: '{}' is not an integer in [{}, {}]", what, shown(t), lo, hi));
    return v;
  }
  // A declared count of `perItem` numbers each: every number takes at least two bytes (a digit and a
  // separator), so a count the rest of the file cannot hold is refused before anything is allocated.
  long count(const std::string& what, long perItem) {
    const long remaining = long(s_.size() - std::min(pos_, s_.size()));
    const long most = (remaining + 1) / 2 / std::max(perItem, 1L);
    const std::string t = need(what);
    long v = 0;
    if (!parseLong(t, v) || v < 0)
      fail(fmt::format("{}: '{}' is not a non-negative integer", what, shown(t)));
    if (v > most)
      fail(fmt::format("{}: {} is more than the rest of the file can hold (at most {})", what, v, most));
    return v;
  }
  // Skips lines up to and including the next empty one (a METADATA block).
  void skipBlock() {
    std::string l;
    line(l);  // the rest of the keyword's line
    while (line(l))
      if (trim(l).empty()) return;
  }
  [[noreturn]] void fail(const std::string& msg, long at = -1) const {
    throw InputError(fmt::format("{}:{}: {}", file_, at < 0 ? tokLine_ : at, msg));
  }
  long tokenLine() const { return tokLine_; }

 private:
  void skipSpace() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) {
      if (s_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }
  const std::string& s_;
  std::string file_;
  std::size_t pos_ = 0;
  long line_ = 1, tokLine_ = 1;  ///< the line pos_ is on; the line of the last token
};

constexpr long kMaxIndex = 2147483646L;

// One cell list, classic ("n size" then n lines "k i1 .. ik") or 5.1 ("n+1 m", OFFSETS, CONNECTIVITY), as
// flat arrays: cell c is nodes[offsets[c] .. offsets[c+1]). Flat, and grown only as numbers are read, so that
// memory stays within a few times the file's size whatever the declared counts say.
struct CellList {
  std::vector<long> offsets{0};
  std::vector<int> nodes;
  std::size_t size() const { return offsets.size() - 1; }
  long length(std::size_t c) const { return offsets[c + 1] - offsets[c]; }
  const int* cell(std::size_t c) const { return nodes.data() + offsets[c]; }
};

CellList readCells(Tokens& t, const std::string& kw, long numPoints) {
  const long n = t.count(kw + " cell count", 1);
  const long size = t.count(kw + " size", 1);
  if (size > kMaxIndex) t.fail(fmt::format("{} size: {} is more than a surface may hold", kw, size));
  CellList cells;
  auto index = [&](const std::string& what) {
    if (numPoints < 0) t.fail(kw + " before POINTS");
    return int(t.integer(what, 0, numPoints - 1));
  };
  if (t.peek() == "OFFSETS") {
    t.need("OFFSETS");
    t.need("OFFSETS type");
    if (n < 1) t.fail(kw + ": the OFFSETS form needs a count ≥ 1 (cells + 1)");
    cells.offsets.clear();
    for (long i = 0; i < n; ++i) {
      const long o = t.integer(kw + " offset", 0, size);
      if (i == 0 && o != 0) t.fail(kw + ": the first offset must be 0");
      if (i > 0 && o < cells.offsets.back()) t.fail(kw + ": offsets must not decrease");
      cells.offsets.push_back(o);
    }
    if (cells.offsets.back() != size)
      t.fail(
          fmt::format("{}: the last offset is {}, the connectivity size {}", kw, cells.offsets.back(), size));
    if (t.need("CONNECTIVITY") != "CONNECTIVITY") t.fail(kw + ": CONNECTIVITY expected after the offsets");
    t.need("CONNECTIVITY type");
    for (long i = 0; i < size; ++i) cells.nodes.push_back(index(kw + " point index"));
    return cells;
  }
  long used = 0;
  for (long c = 0; c < n; ++c) {
    const long k = t.integer(kw + " cell size", 0, size - used - 1);
    used += k + 1;
    for (long i = 0; i < k; ++i) cells.nodes.push_back(index(kw + " point index"));
    cells.offsets.push_back(long(cells.nodes.size()));
  }
  if (used != size) t.fail(fmt::format("{}: the cells hold {} numbers, the header says {}", kw, used, size));
  return cells;
}

void skipNumbers(Tokens& t, long count, const std::string& what) {
  for (long i = 0; i < count; ++i) t.number(what);
}

}  // namespace

SurfaceField readVtkSurface(const std::filesystem::path& file, const std::string& field) {
  const std::string text = readWhole(file);
  const std::string f = file.string();
  Tokens t(text, f);
  std::string l;
  if (!t.line(l) || l.rfind("# vtk DataFile Version", 0) != 0)
    t.fail("not a legacy VTK file (the first line must start with '# vtk DataFile Version')", 1);
  if (!t.line(l)) t.fail("the file ends after the first line", 1);
  if (!t.line(l)) t.fail("the file ends after the title line", 2);
  if (trim(l) != "ASCII")
    t.fail(fmt::format("'{}': only ASCII legacy VTK files are read (save as ASCII)", shown(trim(l))), 3);

  SurfaceField out;
  out.mesh.name = f;
  long numPoints = -1;
  bool dataset = false, found = false;
  std::string section;  // POINT_DATA or CELL_DATA
  long sectionCount = 0;
  std::vector<std::string> names;  // point-data arrays seen, for the message when `field` is missing
  std::string inCells;             // `field` seen as cell data
  std::string tok;
  while (t.next(tok)) {
    const std::string kw = tok;
    if (kw == "DATASET") {
      const std::string type = t.need("DATASET type");
      if (type != "POLYDATA")
        t.fail(fmt::format("DATASET {}: only POLYDATA (a surface) is read", shown(type)));
      dataset = true;
    } else if (!dataset) {
      t.fail(fmt::format("'{}' before DATASET POLYDATA", shown(kw)));
    } else if (kw == "POINTS") {
      if (numPoints >= 0) t.fail("POINTS given twice");
      numPoints = t.count("POINTS count", 3);
      if (numPoints > kMaxIndex) t.fail("POINTS count: too many points");
      t.need("POINTS type");
      out.mesh.points.resize(std::size_t(numPoints));
      for (auto& p : out.mesh.points)
        for (double& c : p) c = t.number("POINTS coordinate");
    } else if (kw == "POLYGONS" || kw == "TRIANGLE_STRIPS" || kw == "VERTICES" || kw == "LINES") {
      const long at = t.tokenLine();
      const CellList cells = readCells(t, kw, numPoints);
      if (kw == "POLYGONS") {
        for (std::size_t c = 0; c < cells.size(); ++c) {
          if (cells.length(c) < 3)
            t.fail(fmt::format("POLYGONS: a polygon with {} points (at least 3)", cells.length(c)), at);
          out.mesh.faceNodes.insert(out.mesh.faceNodes.end(), cells.cell(c), cells.cell(c) + cells.length(c));
          out.mesh.faceOffsets.push_back(int(out.mesh.faceNodes.size()));
        }
      } else if (kw == "TRIANGLE_STRIPS") {
        // Strip (v0, v1, v2, v3, ...) = triangles (v0 v1 v2), (v2 v1 v3), ...: every other one reversed so
        // that all keep the strip's orientation.
        for (std::size_t c = 0; c < cells.size(); ++c) {
          const int* v = cells.cell(c);
          for (long i = 2; i < cells.length(c); ++i)
            i % 2 == 0 ? out.mesh.addFace({v[i - 2], v[i - 1], v[i]})
                       : out.mesh.addFace({v[i - 1], v[i - 2], v[i]});
        }
      }
    } else if (kw == "POINT_DATA" || kw == "CELL_DATA") {
      section = kw;
      sectionCount = t.count(kw + " count", 1);
      if (kw == "POINT_DATA" && sectionCount != numPoints)
        t.fail(fmt::format("POINT_DATA {}: the file has {} points", sectionCount, std::max(numPoints, 0L)));
    } else if (kw == "SCALARS" || kw == "VECTORS" || kw == "NORMALS" || kw == "TENSORS" ||
               kw == "TEXTURE_COORDINATES" || kw == "COLOR_SCALARS" || kw == "FIELD") {
      if (section.empty()) t.fail(fmt::format("{} outside POINT_DATA or CELL_DATA", kw));
      const std::string name = t.need(kw + " name");
      auto take = [&](const std::string& arrayName, long comps, long tuples) {
        const bool want = arrayName == field;
        if (want && section == "CELL_DATA") inCells = arrayName;
        if (section == "POINT_DATA") names.push_back(shown(arrayName));
        if (want && section == "POINT_DATA") {
          if (comps != 1)
            t.fail(fmt::format("field '{}' has {} components; a scalar is needed", field, comps));
          if (found) t.fail(fmt::format("field '{}' given twice", field));
          out.values.resize(std::size_t(tuples));
          for (double& v : out.values) v = t.number(fmt::format("field '{}' value", field));
          found = true;
        } else {
          skipNumbers(t, comps * tuples, fmt::format("{} '{}' value", kw, arrayName));
        }
      };
      if (kw == "FIELD") {
        const long arrays = t.integer("FIELD array count", 0, 100000);
        for (long a = 0; a < arrays; ++a) {
          const std::string arrayName = t.need("FIELD array name");
          const long comps = t.integer("FIELD array components", 1, 1000);
          const long tuples = t.count("FIELD array tuples", comps);
          if (section == "POINT_DATA" && tuples != numPoints && arrayName == field)
            t.fail(fmt::format("field '{}' has {} tuples, the file {} points", field, tuples, numPoints));
          t.need("FIELD array type");
          take(arrayName, comps, tuples);
        }
        continue;
      }
      long comps = 1;
      if (kw == "SCALARS") {
        t.need("SCALARS type");
        const long keywordLine = t.tokenLine();
        long at = 0;
        t.peek(&at);
        if (at == keywordLine) comps = t.integer("SCALARS components", 1, 4);  // optional, on the same line
        if (t.peek() == "LOOKUP_TABLE") {
          t.need("LOOKUP_TABLE");
          t.need("LOOKUP_TABLE name");
        }
      } else if (kw == "VECTORS" || kw == "NORMALS") {
        t.need(kw + " type");
        comps = 3;
      } else if (kw == "TENSORS") {
        t.need(kw + " type");
        comps = 9;
      } else if (kw == "TEXTURE_COORDINATES") {
        comps = t.integer("TEXTURE_COORDINATES dimension", 1, 3);
        t.need(kw + " type");
      } else {  // COLOR_SCALARS
        comps = t.integer("COLOR_SCALARS values", 1, 4);
      }
      take(name, comps, sectionCount);
    } else if (kw == "LOOKUP_TABLE") {
      t.need("LOOKUP_TABLE name");
      skipNumbers(t, 4 * t.count("LOOKUP_TABLE size", 4), "LOOKUP_TABLE value");
    } else if (kw == "METADATA") {
      t.skipBlock();
    } else {
      t.fail(fmt::format("unexpected '{}' (a POLYDATA keyword or attribute was expected)", shown(kw)));
    }
  }
  if (!dataset) t.fail("no DATASET POLYDATA", 4);
  if (numPoints <= 0) throw InputError(fmt::format("{}: no POINTS", f));
  if (out.mesh.numFaces() == 0)
    throw InputError(fmt::format(
        "{}: no POLYGONS or TRIANGLE_STRIPS: a surface with connectivity is needed (a point cloud goes in a "
        ".csv file)",
        f));
  if (!found) {
    std::string have;
    for (const auto& n : names) have += (have.empty() ? "" : ", ") + n;
    throw InputError(fmt::format("{}: no POINT_DATA field '{}'{} (point data: {})", f, field,
                                 inCells.empty() ? "" : " (it is CELL_DATA; point data is needed)",
                                 have.empty() ? "none" : have));
  }
  return out;
}

}  // namespace fsi::coupling
