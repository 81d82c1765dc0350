#pragma once
// Strict parsing of one number token from a text file (Gmsh, OpenFOAM): the whole token must be the number,
// integers must fit their type, reals must be finite. A value that does not fit is reported, never clamped
// or replaced by zero (std::from_chars leaves the output untouched on overflow, which a careless caller reads
// as 0).

#include <string>
#include <string_view>

namespace fsi::structure {

enum class NumberStatus {
  Ok,
  Malformed,   ///< not a number of the expected kind (or trailing characters)
  OutOfRange,  ///< a number, but it does not fit (integer overflow, |real| > DBL_MAX)
  NotFinite,   ///< nan or inf written out
};

/// Decimal integer, optional sign ('+' or '-'). Underflowing reals (1e-400) become 0 or a subnormal, as
/// strtod does: only overflow is out of range.
NumberStatus parseInteger(std::string_view text, long long& value);
NumberStatus parseReal(std::string_view text, double& value);

/// At most 40 characters of `text`, non-printable bytes as '?': for quoting a token (maybe binary garbage
/// read as text) in a message.
std::string printable(std::string_view text);

/// "'1e400' is out of range", "'nan' is not a finite number", "'x' is not an integer" ... for messages.
std::string describeNumberProblem(NumberStatus status, std::string_view text, const char* kind);

}  // namespace fsi::structure
