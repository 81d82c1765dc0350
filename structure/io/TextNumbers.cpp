#include "structure/io/TextNumbers.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>
#include <system_error>

namespace fsi::structure {

namespace {

// std::from_chars accepts no '+'; files written by hand (or by other tools) may have one.
std::string_view dropPlus(std::string_view text) {
  if (text.size() > 1 && text[0] == '+' && text[1] != '-' && text[1] != '+') text.remove_prefix(1);
  return text;
}

}  // namespace

NumberStatus parseInteger(std::string_view text, long long& value) {
  text = dropPlus(text);
  if (text.empty()) return NumberStatus::Malformed;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec == std::errc::result_out_of_range && ptr == end) return NumberStatus::OutOfRange;
  if (ec != std::errc() || ptr != end) return NumberStatus::Malformed;
  return NumberStatus::Ok;
}

NumberStatus parseReal(std::string_view text, double& value) {
  text = dropPlus(text);
  if (text.empty()) return NumberStatus::Malformed;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ptr != end) return NumberStatus::Malformed;
  if (ec == std::errc::result_out_of_range) {
    // from_chars does not say whether the magnitude was too large or too small; strtod does (HUGE_VAL on
    // overflow). Rare path: only numbers beyond double's range get here.
    const std::string copy(text);
    const double v = std::strtod(copy.c_str(), nullptr);
    if (std::isinf(v)) return NumberStatus::OutOfRange;
    value = v;
    return NumberStatus::Ok;
  }
  if (ec != std::errc()) return NumberStatus::Malformed;
  if (!std::isfinite(value)) return NumberStatus::NotFinite;
  return NumberStatus::Ok;
}

std::string printable(std::string_view text) {
  std::string shown(text.substr(0, 40));
  for (char& c : shown)
    if (c < 0x20 || c > 0x7e) c = '?';
  if (text.size() > 40) shown += "...";
  return shown;
}

std::string describeNumberProblem(NumberStatus status, std::string_view text, const char* kind) {
  const std::string shown = printable(text);
  switch (status) {
    case NumberStatus::OutOfRange:
      return fmt::format("'{}' is out of range for {}", shown, kind);
    case NumberStatus::NotFinite:
      return fmt::format("'{}' is not a finite number ({} expected)", shown, kind);
    default:
      return text.empty() ? fmt::format("expected {} but found the end of the file", kind)
                          : fmt::format("expected {} but found '{}'", kind, shown);
  }
}

}  // namespace fsi::structure
