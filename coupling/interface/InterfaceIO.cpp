#include "coupling/interface/InterfaceIO.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <vector>

#include "structure/io/GmshReader.hpp"
#include "structure/io/MeshFileWriters.hpp"
#include "structure/io/TextNumbers.hpp"
#include "structure/model/Error.hpp"

namespace fsi::coupling {

namespace fs = std::filesystem;

namespace {

// Keeps the points used by the faces, renumbered in order of first use.
InterfaceMesh compact(std::string name, const std::vector<std::array<double, 3>>& points,
                      const std::vector<int>& offsets, const std::vector<int>& nodes) {
  InterfaceMesh m;
  m.name = std::move(name);
  std::vector<int> newId(points.size(), -1);
  m.faceOffsets = offsets;
  m.faceNodes.reserve(nodes.size());
  for (int n : nodes) {
    int& id = newId[std::size_t(n)];
    if (id < 0) {
      id = m.numPoints();
      m.points.push_back(points[std::size_t(n)]);
    }
    m.faceNodes.push_back(id);
  }
  return m;
}

// ---------------------------------------------------------------------------------------------------------
// OpenFOAM ASCII files: a tokenizer that knows lines, and the few list forms polyMesh files use.

class FoamLexer {
 public:
  struct Token {
    enum Kind { End, Word, Punct } kind = End;
    std::string_view text;
    int line = 0;
    bool is(char c) const { return kind == Punct && text[0] == c; }
  };

  explicit FoamLexer(fs::path file) : file_(std::move(file)) {
    std::error_code ec;
    std::ifstream in(file_, std::ios::binary);
    if (!in || !fs::is_regular_file(file_, ec)) {
      fs::path gz = file_;
      gz += ".gz";
      if (fs::exists(gz, ec))
        throw InputError(
            fmt::format("{}: compressed polyMesh files are not supported; uncompress them (gunzip "
                        "{}) or set writeCompression off and run foamFormatConvert",
                        gz.string(), gz.string()));
      throw InputError(fmt::format("{}: no such file or not readable", file_.string()));
    }
    const std::uintmax_t size = fs::file_size(file_, ec);
    if (ec) throw InputError(fmt::format("{}: cannot read its size: {}", file_.string(), ec.message()));
    try {
      text_.resize(std::size_t(size));
    } catch (const std::exception&) {  // bad_alloc or length_error
      throw InputError(
          fmt::format("{}: the file ({} bytes) is too large to read into memory", file_.string(), size));
    }
    in.read(text_.data(), std::streamsize(size));
    if (std::uintmax_t(in.gcount()) != size)
      throw InputError(fmt::format("{}: read {} of its {} bytes", file_.string(), in.gcount(), size));
  }

  const fs::path& file() const { return file_; }

  Token next() {
    if (peeked_) {
      peeked_ = false;
      return peek_;
    }
    return scan();
  }
  const Token& peek() {
    if (!peeked_) {
      peek_ = scan();
      peeked_ = true;
    }
    return peek_;
  }

  [[noreturn]] void fail(int line, const std::string& what) const {
    throw InputError(fmt::format("{}:{}: {}", file_.string(), line, what));
  }
  static std::string show(const Token& t) {
    return t.kind == Token::End ? std::string("the end of the file") : fmt::format("'{}'", t.text);
  }
  void expect(char c, const char* what) {
    const Token t = next();
    if (!t.is(c)) fail(t.line, fmt::format("expected '{}' {} but found {}", c, what, show(t)));
  }
  // Numbers are range-checked: an integer that overflows or a real beyond double (1e400), nan or inf is an
  // error, never a silent 0 (std::from_chars leaves its output untouched on overflow).
  long integer(const char* what) {
    const Token t = next();
    long long v = 0;
    const structure::NumberStatus status =
        t.kind == Token::Word ? structure::parseInteger(t.text, v) : structure::NumberStatus::Malformed;
    if (status == structure::NumberStatus::Malformed)
      fail(t.line, fmt::format("expected an integer ({}) but found {}", what, show(t)));
    if (status != structure::NumberStatus::Ok)
      fail(t.line,
           structure::describeNumberProblem(status, t.text, fmt::format("an integer ({})", what).c_str()));
    return long(v);
  }
  double number(const char* what) {
    const Token t = next();
    double v = 0;
    const structure::NumberStatus status =
        t.kind == Token::Word ? structure::parseReal(t.text, v) : structure::NumberStatus::Malformed;
    if (status == structure::NumberStatus::Malformed)
      fail(t.line, fmt::format("expected a number ({}) but found {}", what, show(t)));
    if (status != structure::NumberStatus::Ok)
      fail(t.line, structure::describeNumberProblem(status, t.text, fmt::format("a {}", what).c_str()));
    return v;
  }

  // The FoamFile header dictionary; returns its "class". Refuses binary files.
  std::string header() {
    const Token t = next();
    if (t.kind != Token::Word || t.text != "FoamFile")
      fail(t.line, fmt::format("expected the FoamFile header but found {}", show(t)));
    expect('{', "after FoamFile");
    std::string cls, format;
    for (;;) {
      const Token key = next();
      if (key.is('}')) break;
      if (key.kind != Token::Word)
        fail(key.line, fmt::format("expected a header entry but found {}", show(key)));
      std::string value;
      for (Token v = next(); !v.is(';'); v = next()) {
        if (v.kind == Token::End || v.is('}'))
          fail(v.line, fmt::format("missing ';' after header entry '{}'", key.text));
        value += std::string(v.text);
      }
      if (key.text == "class") cls = value;
      if (key.text == "format") format = value;
    }
    if (format == "binary")
      fail(t.line,
           "binary format is not supported: set 'writeFormat ascii;' in system/controlDict and run "
           "foamFormatConvert");
    if (format != "ascii") fail(t.line, fmt::format("unknown format '{}' (ascii expected)", format));
    return cls;
  }

  // Opens a list: "N (" or "(" (count unknown, returned as -1). A count is checked against the rest of the
  // file (each entry takes at least `minBytesEach` bytes), so a reader may reserve that much.
  long openList(const char* what, std::size_t minBytesEach) {
    long count = -1;
    const int countLine = peek().line;
    if (!peek().is('(')) count = integer(what);
    const Token t = next();
    if (t.is('{')) fail(t.line, fmt::format("uniform list 'N{{...}}' not supported for {}", what));
    if (!t.is('(')) fail(t.line, fmt::format("expected '(' to open the {} list but found {}", what, show(t)));
    if (count < -1) fail(t.line, fmt::format("negative {} count", what));
    const std::size_t left = text_.size() - pos_;
    if (count > 0 && static_cast<unsigned long>(count) > left / minBytesEach)
      fail(countLine,
           fmt::format("the {} list announces {} entries, but the {} bytes left in the file can hold at "
                       "most {}",
                       what, count, left, left / minBytesEach));
    return count;
  }
  // True (and consumes it) at the ')' closing a list.
  bool closes() {
    if (peek().kind == Token::End) fail(peek().line, "unexpected end of file inside a list (missing ')')");
    if (!peek().is(')')) return false;
    next();
    return true;
  }
  void checkCount(long expected, long found, int line, const char* what) const {
    if (expected >= 0 && expected != found)
      fail(line, fmt::format("the {} list announces {} entries but has {}", what, expected, found));
  }
  int line() { return peek().line; }

 private:
  Token scan() {
    skipSpaceAndComments();
    Token t;
    t.line = line_;
    if (pos_ >= text_.size()) return t;
    const char c = text_[pos_];
    if (std::string_view("(){};[]").find(c) != std::string_view::npos) {
      t.kind = Token::Punct;
      t.text = std::string_view(text_).substr(pos_++, 1);
      return t;
    }
    const std::size_t begin = pos_;
    if (c == '"') {
      const std::size_t close = text_.find('"', pos_ + 1);
      pos_ = close == std::string::npos ? text_.size() : close + 1;
    } else {
      while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_])) &&
             std::string_view("(){};[]\"").find(text_[pos_]) == std::string_view::npos &&
             !(text_[pos_] == '/' && pos_ + 1 < text_.size() &&
               (text_[pos_ + 1] == '/' || text_[pos_ + 1] == '*')))
        ++pos_;
    }
    t.kind = Token::Word;
    t.text = std::string_view(text_).substr(begin, pos_ - begin);
    return t;
  }
  void skipSpaceAndComments() {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '\n') {
        ++line_;
        ++pos_;
      } else if (std::isspace(static_cast<unsigned char>(c))) {
        ++pos_;
      } else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '/') {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
      } else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '*') {
        const std::size_t end = text_.find("*/", pos_ + 2);
        const std::size_t stop = end == std::string::npos ? text_.size() : end + 2;
        line_ += int(std::count(text_.begin() + long(pos_), text_.begin() + long(stop), '\n'));
        pos_ = stop;
      } else {
        break;
      }
    }
  }

  fs::path file_;
  std::string text_;
  std::size_t pos_ = 0;
  int line_ = 1;
  Token peek_;
  bool peeked_ = false;
};

struct Patch {
  std::string name;
  long nFaces = -1, startFace = -1;
  int line = 0;
};

std::vector<Patch> readBoundary(const fs::path& file) {
  FoamLexer lex(file);
  lex.header();
  const long count = lex.openList("patch", 16);  // "p{nFaces 0;startFace 0;}"
  std::vector<Patch> patches;
  while (!lex.closes()) {
    const FoamLexer::Token name = lex.next();
    if (name.kind != FoamLexer::Token::Word)
      lex.fail(name.line, fmt::format("expected a patch name but found {}", FoamLexer::show(name)));
    Patch p;
    p.name = std::string(name.text);
    p.line = name.line;
    lex.expect('{', "after the patch name");
    for (;;) {
      const FoamLexer::Token key = lex.next();
      if (key.is('}')) break;
      if (key.kind != FoamLexer::Token::Word)
        lex.fail(key.line,
                 fmt::format("patch '{}': expected an entry but found {}", p.name, FoamLexer::show(key)));
      if (lex.peek().is('{')) {  // a sub-dictionary: skip it
        int depth = 0;
        do {
          const FoamLexer::Token t = lex.next();
          if (t.kind == FoamLexer::Token::End) lex.fail(t.line, "unexpected end of file (missing '}')");
          depth += t.is('{') ? 1 : (t.is('}') ? -1 : 0);
        } while (depth > 0);
        continue;
      }
      std::vector<FoamLexer::Token> value;
      for (FoamLexer::Token v = lex.next(); !v.is(';'); v = lex.next()) {
        if (v.kind == FoamLexer::Token::End || v.is('}'))
          lex.fail(v.line, fmt::format("patch '{}': missing ';' after '{}'", p.name, key.text));
        value.push_back(v);
      }
      if (key.text == "nFaces" || key.text == "startFace") {
        long long n = -1;
        const bool ok = value.size() == 1 &&
                        structure::parseInteger(value[0].text, n) == structure::NumberStatus::Ok && n >= 0;
        if (!ok)
          lex.fail(key.line, fmt::format("patch '{}': {} must be one non-negative integer (at most {})",
                                         p.name, key.text, LLONG_MAX));
        (key.text == "nFaces" ? p.nFaces : p.startFace) = long(n);
      }
    }
    if (p.nFaces < 0 || p.startFace < 0)
      lex.fail(p.line, fmt::format("patch '{}' lacks {}", p.name, p.nFaces < 0 ? "nFaces" : "startFace"));
    patches.push_back(p);
  }
  lex.checkCount(count, long(patches.size()), lex.line(), "patch");
  return patches;
}

std::vector<std::array<double, 3>> readPoints(const fs::path& file) {
  FoamLexer lex(file);
  lex.header();
  const long count = lex.openList("point", 7);  // "(0 0 0)"
  std::vector<std::array<double, 3>> points;
  if (count > 0) points.reserve(std::size_t(count));
  while (!lex.closes()) {
    lex.expect('(', "to open a point");
    std::array<double, 3> p;
    for (double& x : p) x = lex.number("coordinate");
    lex.expect(')', "to close a point (3 coordinates)");
    points.push_back(p);
  }
  lex.checkCount(count, long(points.size()), lex.line(), "point");
  return points;
}

// Faces (faceList "n(a b c ...)" or the two label lists of faceCompactList) as offsets and nodes; every
// label is checked against the number of points, with its line.
void readFaces(const fs::path& file, long numPoints, std::vector<int>& offsets, std::vector<int>& nodes) {
  FoamLexer lex(file);
  const std::string cls = lex.header();
  offsets.assign(1, 0);
  nodes.clear();
  auto label = [&](long face) {
    const int line = lex.line();
    const long v = lex.integer("point label");
    if (v < 0 || v >= numPoints)
      lex.fail(line, fmt::format("face {} refers to point {}, but the points file has {} points", face, v,
                                 numPoints));
    return int(v);
  };
  if (cls == "faceCompactList") {
    std::vector<long> starts;
    const long n = lex.openList("face offset", 2);
    while (!lex.closes()) starts.push_back(lex.integer("face offset"));
    lex.checkCount(n, long(starts.size()), lex.line(), "face offset");
    const long m = lex.openList("face label", 2);
    long face = 0;
    while (!lex.closes()) {
      while (face + 1 < long(starts.size()) && long(nodes.size()) >= starts[std::size_t(face) + 1]) ++face;
      nodes.push_back(label(face));
    }
    lex.checkCount(m, long(nodes.size()), lex.line(), "face label");
    // Offsets run from 0 to the number of labels: otherwise labels would be lost or shifted between faces.
    if (!starts.empty() && (starts.front() != 0 || starts.back() != long(nodes.size())))
      lex.fail(lex.line(), fmt::format("face offsets run from {} to {}, but must run from 0 to the number of "
                                       "labels, {}",
                                       starts.front(), starts.back(), nodes.size()));
    for (std::size_t f = 1; f < starts.size(); ++f) {
      if (starts[f] < starts[f - 1] || starts[f] > long(nodes.size()))
        lex.fail(lex.line(),
                 fmt::format("face offsets are not increasing within the labels at face {}", f - 1));
      offsets.push_back(int(starts[f]));
    }
    return;
  }
  const long count = lex.openList("face", 8);  // "3(0 1 2)"
  if (count > 0) offsets.reserve(std::size_t(count) + 1);
  while (!lex.closes()) {
    const long face = long(offsets.size()) - 1;
    const int line = lex.line();
    const long n = lex.integer("number of face vertices");
    lex.expect('(', "to open a face");
    for (long k = 0; k < n; ++k) nodes.push_back(label(face));
    lex.expect(')', "to close a face (as many labels as announced)");
    if (n < 3) lex.fail(line, fmt::format("face {} has {} vertices (at least 3 needed)", face, n));
    offsets.push_back(int(nodes.size()));
  }
  lex.checkCount(count, long(offsets.size()) - 1, lex.line(), "face");
}

// The number of internal faces: the length of the `neighbour` list (one entry per internal face), or -1 when
// the polyMesh has no neighbour file (a boundary-only mesh written by a tool or a test).
// `line` is that of the list's count, for messages.
long internalFaceCount(const fs::path& dir, int& line) {
  std::error_code ec;
  const fs::path file = dir / "neighbour";
  if (!fs::exists(file, ec)) return -1;
  FoamLexer lex(file);
  lex.header();
  line = lex.line();
  long count = lex.openList("neighbour", 2);  // "0\n"
  if (count >= 0) return count;
  for (count = 0; !lex.closes(); ++count) lex.integer("cell label");
  return count;
}

// Every patch of the boundary file, not only the one asked for, as OpenFOAM's polyBoundaryMesh checks them:
// names unique; each patch's faces inside the faces file and after the internal faces; the patches one after
// the other without gap or overlap, from the end of the internal faces to the last face.
void checkPatches(const std::vector<Patch>& patches, const fs::path& boundaryFile, const fs::path& facesFile,
                  long numFaces, long numInternal, const fs::path& neighbourFile, int neighbourLine) {
  const std::string b = boundaryFile.string();
  if (numInternal > numFaces)
    throw InputError(fmt::format("{}:{}: lists {} internal faces, but {} has only {} faces",
                                 neighbourFile.string(), neighbourLine, numInternal, facesFile.string(),
                                 numFaces));
  long next = numInternal >= 0 ? numInternal : (patches.empty() ? 0 : patches.front().startFace);
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const Patch& p = patches[i];
    // Written so that it cannot overflow: startFace and nFaces may each be near LONG_MAX.
    if (p.startFace > numFaces || p.nFaces > numFaces - p.startFace)
      throw InputError(fmt::format("{}:{}: patch '{}' has {} faces from face {}, but {} has {} faces", b,
                                   p.line, p.name, p.nFaces, p.startFace, facesFile.string(), numFaces));
    if (numInternal >= 0 && p.startFace < numInternal)
      throw InputError(
          fmt::format("{}:{}: patch '{}' starts at face {}, inside the {} internal faces (the "
                      "length of {}); boundary faces follow the internal ones",
                      b, p.line, p.name, p.startFace, numInternal, neighbourFile.string()));
    if (p.startFace != next)
      throw InputError(fmt::format(
          "{}:{}: patch '{}' starts at face {}, but {} ends at face {}; patches must follow each other "
          "without gap or overlap",
          b, p.line, p.name, p.startFace,
          i == 0 ? std::string("the internal faces' list") : fmt::format("patch '{}'", patches[i - 1].name),
          next));
    next = p.startFace + p.nFaces;
  }
  if (!patches.empty() && next != numFaces)
    throw InputError(fmt::format(
        "{}:{}: the last patch '{}' ends at face {}, but {} has {} faces: faces {} to "
        "{} belong to no patch",
        b, patches.back().line, patches.back().name, next, facesFile.string(), numFaces, next, numFaces - 1));
}

bool endsWithMsh(const std::string& s) {
  if (s.size() < 4) return false;
  std::string tail = s.substr(s.size() - 4);
  std::transform(tail.begin(), tail.end(), tail.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return tail == ".msh";
}

}  // namespace

namespace {

InterfaceMesh readOpenFoamPatchUnguarded(const fs::path& caseDir, const std::string& patch) {
  const fs::path dir = caseDir / "constant" / "polyMesh";
  std::error_code ec;
  for (const char* name : {"points", "faces", "boundary"})
    if (!fs::exists(dir / name, ec) && !fs::exists(dir / (std::string(name) + ".gz"), ec))
      throw InputError(
          fmt::format("{}: no such file (is {} an OpenFOAM case?)", (dir / name).string(), caseDir.string()));
  const fs::path boundaryFile = dir / "boundary";
  const std::vector<Patch> patches = readBoundary(boundaryFile);
  for (std::size_t i = 0; i < patches.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (patches[j].name == patches[i].name)
        throw InputError(
            fmt::format("{}:{}: patch '{}' is defined twice (first at line {}); patch names must "
                        "be unique",
                        boundaryFile.string(), patches[i].line, patches[i].name, patches[j].line));
  const auto it =
      std::find_if(patches.begin(), patches.end(), [&](const Patch& p) { return p.name == patch; });
  if (it == patches.end()) {
    std::string names;
    for (const Patch& p : patches) names += (names.empty() ? "" : ", ") + p.name;
    throw InputError(fmt::format("{}: no patch '{}'; the patches are: {}", boundaryFile.string(), patch,
                                 names.empty() ? "(none)" : names));
  }
  if (it->nFaces == 0)
    throw InputError(fmt::format("{}:{}: patch '{}' has no faces", boundaryFile.string(), it->line, patch));
  const std::vector<std::array<double, 3>> points = readPoints(dir / "points");
  std::vector<int> offsets, nodes;
  readFaces(dir / "faces", long(points.size()), offsets, nodes);
  const long numFaces = long(offsets.size()) - 1;
  int neighbourLine = 0;
  const long numInternal = internalFaceCount(dir, neighbourLine);
  checkPatches(patches, boundaryFile, dir / "faces", numFaces, numInternal, dir / "neighbour", neighbourLine);
  const int first = offsets[std::size_t(it->startFace)];
  std::vector<int> patchOffsets,
      patchNodes(nodes.begin() + first, nodes.begin() + offsets[std::size_t(it->startFace + it->nFaces)]);
  for (long f = it->startFace; f <= it->startFace + it->nFaces; ++f)
    patchOffsets.push_back(offsets[std::size_t(f)] - first);
  return compact(caseDir.string() + ":" + patch, points, patchOffsets, patchNodes);
}

}  // namespace

InterfaceMesh readOpenFoamPatch(const fs::path& caseDir, const std::string& patch) {
  try {
    return readOpenFoamPatchUnguarded(caseDir, patch);
  } catch (const std::bad_alloc&) {
    // The lists are checked against the file sizes; this machine has not even that much memory.
    throw InputError(fmt::format("{}: not enough memory to read patch '{}'", caseDir.string(), patch));
  }
}

InterfaceMesh readGmshInterface(const fs::path& file, const std::string& group) {
  const structure::MeshData data = structure::readGmsh(file, file.stem().string());
  std::vector<int> triangles;
  if (group.empty()) {
    for (int t = 0; t < int(data.triangles.size()); ++t) triangles.push_back(t);
  } else {
    const auto it = data.triangleGroups.find(group);
    if (it == data.triangleGroups.end()) {
      std::string names;
      for (const auto& [name, members] : data.triangleGroups) names += (names.empty() ? "" : ", ") + name;
      throw InputError(fmt::format("{}: no physical surface group '{}'; the surface groups are: {}",
                                   file.string(), group, names.empty() ? "(none)" : names));
    }
    triangles = it->second;
  }
  if (triangles.empty())
    throw InputError(fmt::format("{}: no triangles{}", file.string(),
                                 group.empty() ? std::string() : " in group '" + group + "'"));
  std::vector<int> offsets{0}, nodes;
  for (int t : triangles) {
    for (int n : data.triangles[std::size_t(t)]) nodes.push_back(n);
    offsets.push_back(int(nodes.size()));
  }
  return compact(group.empty() ? file.string() : file.string() + ":" + group, data.points, offsets, nodes);
}

namespace {

bool isDirectory(const std::string& path) {
  std::error_code ec;  // a name too long or unreadable is no directory (the non-throwing overload)
  return fs::is_directory(path, ec);
}

InterfaceMesh readInterfaceUnguarded(const std::string& spec) {
  const char* forms = "expected FILE.msh, FILE.msh:GROUP or CASE_DIR:PATCH";
  if (spec.empty()) throw InputError(fmt::format("empty interface mesh name ({})", forms));
  InterfaceMesh m;
  if (endsWithMsh(spec)) {
    m = readGmshInterface(spec);
  } else if (const std::size_t colon = spec.rfind(':'); colon != std::string::npos) {
    const std::string head = spec.substr(0, colon), tail = spec.substr(colon + 1);
    if (tail.empty()) throw InputError(fmt::format("'{}': nothing after ':' ({})", spec, forms));
    if (endsWithMsh(head))
      m = readGmshInterface(head, tail);
    else if (isDirectory(head))
      m = readOpenFoamPatch(head, tail);
    else
      throw InputError(
          fmt::format("'{}': {} is neither a .msh file nor a directory ({})", spec, head, forms));
  } else if (isDirectory(spec)) {
    throw InputError(fmt::format("'{}' is a directory: name the OpenFOAM patch as {}:PATCH", spec, spec));
  } else {
    throw InputError(fmt::format("'{}': {}", spec, forms));
  }
  m.name = spec;
  return m;
}

}  // namespace

InterfaceMesh readInterface(const std::string& spec) {
  try {
    return readInterfaceUnguarded(spec);
  } catch (const std::bad_alloc&) {
    // The readers allocate at most a small multiple of the file sizes; this machine has not that much.
    throw InputError(fmt::format("{}: not enough memory to read this interface mesh", spec));
  }
}

InterfaceMesh readStlSurface(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("{}: cannot be read", file.string()));
  InterfaceMesh m;
  m.name = file.string();
  std::map<std::array<double, 3>, int> index;
  std::vector<int> facet;
  std::string line;
  long lineNo = 0;
  bool solid = false;
  while (std::getline(in, line)) {
    ++lineNo;
    std::istringstream words(line);
    std::string key;
    if (!(words >> key)) continue;
    if (!solid) {
      if (key != "solid")
        throw InputError(
            fmt::format("{}:{}: not an ASCII STL (no 'solid' first; a binary STL must be converted, "
                        "e.g. with surfaceConvert)",
                        file.string(), lineNo));
      solid = true;
      continue;
    }
    if (key != "vertex") continue;
    std::array<double, 3> x{};
    if (!(words >> x[0] >> x[1] >> x[2]) || !std::isfinite(x[0]) || !std::isfinite(x[1]) ||
        !std::isfinite(x[2]))
      throw InputError(fmt::format("{}:{}: a vertex needs three finite numbers", file.string(), lineNo));
    const auto [it, added] = index.emplace(x, int(m.points.size()));
    if (added) m.points.push_back(x);
    facet.push_back(it->second);
    if (facet.size() == 3) {
      m.addFace({facet[0], facet[2], facet[1]});  // the fluid side's orientation
      facet.clear();
    }
  }
  if (!facet.empty())
    throw InputError(fmt::format("{}: the last facet has {} vertices, not 3", file.string(), facet.size()));
  if (m.numFaces() == 0) throw InputError(fmt::format("{}: no facets", file.string()));
  return m;
}

void writeInterfaceStl(const InterfaceMesh& mesh, const std::vector<double>& displacement,
                       const std::filesystem::path& file) {
  if (!displacement.empty() && displacement.size() != 3 * mesh.points.size())
    throw std::invalid_argument(fmt::format("writeInterfaceStl: {} displacement values for {} points of {}",
                                            displacement.size(), mesh.points.size(), mesh.name));
  auto at = [&](int n) {
    std::array<double, 3> x = mesh.points[std::size_t(n)];
    if (!displacement.empty())
      for (std::size_t k = 0; k < 3; ++k) x[k] += displacement[3 * std::size_t(n) + k];
    return x;
  };
  std::ofstream out(file);
  if (!out) throw std::runtime_error(fmt::format("{}: cannot be written", file.string()));
  std::string name = mesh.name.empty() ? std::string("interface") : mesh.name;
  std::replace_if(
      name.begin(), name.end(), [](unsigned char c) { return std::isspace(c) != 0; }, '_');
  out << "solid " << name << '\n';
  auto facet = [&](const std::array<double, 3>& a, const std::array<double, 3>& b,
                   const std::array<double, 3>& c) { structure::writeStlFacet(out, a, b, c); };
  for (int f = 0; f < mesh.numFaces(); ++f) {
    const int* v = mesh.face(f);
    const int n = mesh.faceSize(f);
    if (n == 3) {
      facet(at(v[0]), at(v[2]), at(v[1]));  // the other way round
      continue;
    }
    std::array<double, 3> centre{0, 0, 0};
    for (int j = 0; j < n; ++j)
      for (std::size_t k = 0; k < 3; ++k) centre[k] += at(v[j])[k] / n;
    for (int j = 0; j < n; ++j) facet(centre, at(v[(j + 1) % n]), at(v[j]));
  }
  out << "endsolid " << name << '\n';
  if (!out) throw std::runtime_error(fmt::format("{}: writing failed (disk full?)", file.string()));
}

}  // namespace fsi::coupling
