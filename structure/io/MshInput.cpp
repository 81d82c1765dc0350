#include "structure/io/MshInput.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>

#include "structure/io/TextNumbers.hpp"
#include "structure/model/Error.hpp"

namespace fsi::structure {

namespace {

bool isSpace(char c) {
  return c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

}  // namespace

MshInput::MshInput(std::string fileName, std::string bytes)
    : file_(std::move(fileName)), bytes_(std::move(bytes)) {}

void MshInput::setBinary(bool swapBytes) {
  binary_ = true;
  swap_ = swapBytes;
}

std::string MshInput::where(std::size_t mark) const {
  return binary_ ? fmt::format("{}, byte {}", file_, mark) : fmt::format("{}:{}", file_, mark);
}

void MshInput::fail(const std::string& what) const {
  const std::string section = section_.empty() ? std::string() : fmt::format("in ${}: ", section_);
  throw InputError(fmt::format("{}: {}{}", where(mark()), section, what));
}

void MshInput::skipSpace() {
  while (pos_ < bytes_.size() && isSpace(bytes_[pos_])) {
    if (bytes_[pos_] == '\n') ++line_;
    ++pos_;
  }
}

std::string_view MshInput::token() {
  skipSpace();
  markOffset_ = pos_;
  markLine_ = line_;
  const std::size_t begin = pos_;
  while (pos_ < bytes_.size() && !isSpace(bytes_[pos_])) ++pos_;
  return std::string_view(bytes_).substr(begin, pos_ - begin);
}

bool MshInput::atEnd() {
  skipSpace();
  return pos_ >= bytes_.size();
}

long long MshInput::textInteger(const char* what, long long lo, long long hi) {
  const std::string_view t = token();
  long long v = 0;
  const NumberStatus status = parseInteger(t, v);
  if (status != NumberStatus::Ok) fail(describeNumberProblem(status, t, what));
  if (v < lo || v > hi) fail(fmt::format("{} is {}, outside [{}, {}]", what, v, lo, hi));
  return v;
}

double MshInput::textReal(const char* what) {
  const std::string_view t = token();
  double v = 0;
  const NumberStatus status = parseReal(t, v);
  if (status != NumberStatus::Ok) fail(describeNumberProblem(status, t, what));
  return v;
}

std::string MshInput::quoted(const char* what) {
  skipSpace();
  markOffset_ = pos_;
  markLine_ = line_;
  if (pos_ >= bytes_.size() || bytes_[pos_] != '"') fail(fmt::format("expected {} in double quotes", what));
  const std::size_t close = bytes_.find_first_of("\"\n", pos_ + 1);
  if (close == std::string::npos || bytes_[close] != '"')
    fail(fmt::format("{} has no closing '\"' on its line", what));
  std::string s = bytes_.substr(pos_ + 1, close - pos_ - 1);
  pos_ = close + 1;
  return s;
}

void MshInput::expect(std::string_view expected) {
  const std::string_view t = token();
  if (t != expected)
    fail(t.empty() ? fmt::format("expected {} but found the end of the file", expected)
                   : fmt::format("expected {} but found '{}' (the counts or sizes before it are wrong, or "
                                 "data was added or lost)",
                                 expected, printable(t)));
}

void MshInput::endLine() {
  while (pos_ < bytes_.size() && bytes_[pos_] != '\n') {
    if (!isSpace(bytes_[pos_])) {
      markOffset_ = pos_;
      fail("unexpected characters at the end of a line before binary data");
    }
    ++pos_;
  }
  if (pos_ >= bytes_.size()) {
    markOffset_ = pos_;
    fail("the file ends where binary data should start");
  }
  ++pos_;
  ++line_;
}

void MshInput::skipSection(std::string_view name) {
  const std::string end = "$End" + std::string(name);
  std::size_t at = pos_;
  for (;;) {
    at = bytes_.find(end, at);
    if (at == std::string::npos) fail(fmt::format("section ${} has no {}", name, end));
    // The marker must be a whole token (not the start of "$EndNodesXYZ" or inside a longer word).
    const std::size_t after = at + end.size();
    if ((at == 0 || isSpace(bytes_[at - 1])) && (after == bytes_.size() || isSpace(bytes_[after]))) break;
    at = after;
  }
  line_ += std::size_t(
      std::count(bytes_.begin() + std::ptrdiff_t(pos_), bytes_.begin() + std::ptrdiff_t(at), '\n'));
  pos_ = at + end.size();
}

const char* MshInput::rawBytes(std::size_t n, const char* what) {
  markOffset_ = pos_;
  if (remaining() < n)
    fail(fmt::format("the file ends inside {} ({} bytes needed, {} left)", what, n, remaining()));
  const char* p = bytes_.data() + pos_;
  pos_ += n;
  return p;
}

template <class T>
T MshInput::raw(const char* what) {
  const char* p = rawBytes(sizeof(T), what);
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (swap_) std::reverse(b, b + sizeof(T));
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

long long MshInput::int32(const char* what, long long lo, long long hi) {
  if (!binary_) return textInteger(what, lo, hi);
  const long long v = raw<std::int32_t>(what);
  if (v < lo || v > hi) fail(fmt::format("{} is {}, outside [{}, {}]", what, v, lo, hi));
  return v;
}

long long MshInput::size(const char* what, long long lo, long long hi) {
  if (!binary_) return textInteger(what, lo, hi);
  const std::uint64_t v = raw<std::uint64_t>(what);
  if (v > std::uint64_t(hi) || static_cast<long long>(v) < lo)
    fail(fmt::format("{} is {}, outside [{}, {}]", what, v, lo, hi));
  return static_cast<long long>(v);
}

double MshInput::real(const char* what) {
  if (!binary_) return textReal(what);
  const double v = raw<double>(what);
  if (!std::isfinite(v)) fail(fmt::format("{} is {}, not a finite number", what, v));
  return v;
}

void MshInput::skipReals(std::size_t n, const char* what) {
  if (binary_) {
    rawBytes(n * sizeof(double), what);
    return;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::string_view t = token();
    double v = 0;
    const NumberStatus status = parseReal(t, v);
    if (status == NumberStatus::Malformed) fail(describeNumberProblem(status, t, what));
  }
}

void MshInput::checkCount(long long count, std::size_t minBytesEach, const char* what) {
  if (count < 0) fail(fmt::format("negative number of {}: {}", what, count));
  if (static_cast<unsigned long long>(count) > remaining() / minBytesEach)
    fail(fmt::format("{} {} announced, but the {} bytes left in the file can hold at most {}", count, what,
                     remaining(), remaining() / minBytesEach));
}

}  // namespace fsi::structure
