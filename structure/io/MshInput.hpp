#pragma once
// MshInput: a cursor over the bytes of a Gmsh MSH file, for MshReader. It reads text tokens (with their line)
// and, in binary files, raw values (with their byte offset), and never reads outside the file: every
// problem is an fsi::InputError naming the file, the line (ASCII) or byte offset (binary), the section and
// what was expected.
//
// The file is held in memory. Counts announced by the file are checked against the bytes left before
// anything is allocated for them (checkCount), so a hostile count cannot make the reader allocate more than
// a small multiple of the file's size.

#include <cstddef>
#include <string>
#include <string_view>

namespace fsi::structure {

class MshInput {
 public:
  MshInput(std::string fileName, std::string bytes);

  const std::string& fileName() const { return file_; }
  /// The section being read ("Nodes"), named in messages.
  void setSection(std::string_view name) { section_ = name; }
  /// From now on typed values are raw binary (byte-swapped if `swapBytes`) and messages give byte offsets.
  void setBinary(bool swapBytes);
  bool binary() const { return binary_; }

  // --- Text (ASCII files, and the text parts of binary files) -------------------------------------------
  /// The next white-space separated token; empty at the end of the file.
  std::string_view token();
  /// True if only white space is left.
  bool atEnd();
  /// A decimal integer token in [lo, hi]; `what` names it in messages ("a node tag").
  long long textInteger(const char* what, long long lo, long long hi);
  /// A real token (finite).
  double textReal(const char* what);
  /// A double-quoted string on one line ("canopy"), without the quotes.
  std::string quoted(const char* what);
  /// The next token must be `expected` (a section end such as "$EndNodes").
  void expect(std::string_view expected);
  /// Binary files: the rest of the current line (blanks only) and its '\n', after which raw data starts.
  void endLine();
  /// Skips to just after "$End<name>" (a section this reader does not need).
  void skipSection(std::string_view name);

  // --- Typed values: a text token in an ASCII file, a raw value in a binary one --------------------------
  /// A 4-byte int in binary files.
  long long int32(const char* what, long long lo, long long hi);
  /// An 8-byte unsigned (size_t) in binary files.
  long long size(const char* what, long long lo, long long hi);
  /// A finite real, 8 bytes in binary files.
  double real(const char* what);
  /// `n` reals nobody uses (bounding boxes, parametric coordinates): they must be there and be numbers.
  void skipReals(std::size_t n, const char* what);

  /// Fails unless `count` items of at least `minBytesEach` bytes each fit into what is left of the file.
  void checkCount(long long count, std::size_t minBytesEach, const char* what);
  std::size_t remaining() const { return bytes_.size() - pos_; }

  /// Throws an fsi::InputError located at the last token or value read.
  [[noreturn]] void fail(const std::string& what) const;
  /// Where the last token or value started: its line (ASCII) or byte offset (binary).
  std::size_t mark() const { return binary_ ? markOffset_ : markLine_; }
  /// "file:12" or "file, byte 345", for a position saved with mark().
  std::string where(std::size_t mark) const;

 private:
  void skipSpace();
  const char* rawBytes(std::size_t n, const char* what);
  template <class T>
  T raw(const char* what);

  std::string file_;
  std::string bytes_;
  std::string section_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
  std::size_t markOffset_ = 0, markLine_ = 1;
  bool binary_ = false, swap_ = false;
};

}  // namespace fsi::structure
