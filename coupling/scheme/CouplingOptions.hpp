#pragma once
// CouplingOptions: the options of a coupled run as one table — key, type, default, valid range or choices,
// a one-line description and when the option has an effect — and the validation of user input against it.
// It knows no host: the OpenFOAM adapter turns its function-object dictionary into key -> tokens
// (OptionTokens), adds the keys OpenFOAM itself reads, and calls OptionSchema::validate(), which stops at the
// first unknown key (naming the nearest valid key and all valid keys) or bad value (naming the key, the value
// and the valid range). The accelerations an implicit scheme can use, their names (and so the "did you mean"
// of `acceleration`) and their own options come from their registry (acceleration/AccelerationRegistry),
// so that adding one touches nothing here. Ranges agree with the checks of the library classes
// (the accelerations, CouplingScheme, StructureParticipant); tests/unit/test_coupling_options.cpp checks it.

#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "coupling/scheme/Acceleration.hpp"
#include "coupling/scheme/CouplingScheme.hpp"
#include "coupling/scheme/Equilibrium.hpp"

namespace fsi::coupling {

enum class OptionType {
  Switch,    ///< yes/no, on/off, true/false (OpenFOAM's Switch words)
  Integer,   ///< a whole number
  Real,      ///< a finite number
  Choice,    ///< one word of `choices`
  Text,      ///< one word or string (a file name)
  WordList,  ///< (a b c) or a single word
  Any        ///< not checked (keys the host reads itself)
};
const char* toString(OptionType t);

/// One end of a numeric range.
struct Bound {
  double value = 0;
  bool inclusive = true;
};

/// The option has an effect only if `key` is given (empty `values`) or has one of `values`.
struct OptionCondition {
  std::string key;
  std::vector<std::string> values;
};

struct OptionSpec {
  std::string key;
  OptionType type = OptionType::Any;
  std::string defaultValue;  ///< read like user input when the key is absent; empty: none
  std::string defaultNote;   ///< describes a default the host computes (no defaultValue then)
  bool required = false;
  std::optional<Bound> lower, upper;  ///< Integer and Real
  std::vector<std::string> choices;   ///< Choice; Integer, Real: words accepted instead of a number
  std::string description;            ///< one line
  std::vector<OptionCondition> when;  ///< all must hold for the option to have an effect
  std::string refusal;                ///< non-empty: a known key that must not be given, and why
  bool host = false;                  ///< read by the host itself (listed apart in messages)

  /// "0 < omega <= 1", "integer >= 1", "one of staggered implicit", "yes or no", ...
  std::string rangeText() const;
  /// "0.5", "computed: 0.25 x mean structure edge length", "required", "none".
  std::string defaultText() const;
};

/// A bad option: what() names the key, the value given and the valid range, choices or keys.
class OptionError : public std::invalid_argument {
 public:
  OptionError(const std::string& key, const std::string& message)
      : std::invalid_argument(message), key_(key) {}
  const std::string& key() const { return key_; }

 private:
  std::string key_;
};

/// The user's options in their order: key and its tokens (`omega 0.5;` -> {"omega", {"0.5"}}, a list
/// `patches (a b);` -> {"patches", {"(", "a", "b", ")"}}).
using OptionTokens = std::vector<std::pair<std::string, std::vector<std::string>>>;

/// Validated values: every given key passed its type and range check; absent keys with a default have it.
class OptionValues {
 public:
  bool given(const std::string& key) const;  ///< set by the user
  bool has(const std::string& key) const;    ///< given, or absent with a default that applies
  double real(const std::string& key) const;
  long integer(const std::string& key) const;
  /// True when an Integer or Real option holds one of its words (`auto`) rather than a number.
  bool isWord(const std::string& key) const;
  bool flag(const std::string& key) const;
  const std::string& text(const std::string& key) const;  ///< Choice or Text
  std::vector<std::string> words(const std::string& key) const;
  /// One line per option that was given but has no effect with the other options (e.g. omega with the
  /// staggered scheme); the host prints them.
  const std::vector<std::string>& warnings() const { return warnings_; }

  /// The parsed form of one option.
  struct Value {
    OptionType type = OptionType::Any;
    bool given = false;
    double number = 0;               // Integer, Real
    bool flag = false;               // Switch
    std::vector<std::string> words;  // Choice, Text: one word; WordList; Any: the tokens
  };

 private:
  friend class OptionSchema;
  const Value& at(const std::string& key, const char* what) const;
  std::map<std::string, Value> values_;
  std::vector<std::string> warnings_;
};

class OptionSchema {
 public:
  OptionSchema& add(OptionSpec spec);
  OptionSchema& add(const std::vector<OptionSpec>& specs);
  /// Who reads the `host` keys ("OpenFOAM"), for messages.
  OptionSchema& setHostName(std::string name) {
    hostName_ = std::move(name);
    return *this;
  }
  const std::vector<OptionSpec>& specs() const { return specs_; }
  /// Every key once, in table order.
  std::vector<std::string> keys() const;
  /// Checks every key and value; throws OptionError at the first problem.
  OptionValues validate(const OptionTokens& tokens) const;

 private:
  const OptionSpec* applicable(const std::string& key, const OptionTokens& tokens) const;
  std::string conditionValue(const std::string& key, const OptionTokens& tokens) const;
  std::vector<OptionSpec> specs_;
  std::string hostName_ = "host";
};

/// Table rows for the option tables of this file and of the accelerations' entries (AccelerationRegistry):
/// a real or integer option with an optional range, and the relaxation factor omega, 0 < omega <= 1.
OptionSpec realOption(std::string key, std::string def, std::optional<Bound> lo, std::optional<Bound> hi,
                      std::string description);
OptionSpec integerOption(std::string key, std::string def, std::optional<Bound> lo, std::optional<Bound> hi,
                         std::string description);
OptionSpec omegaOption(const std::string& def, const std::string& description);

/// The coupling options of a coupled run (the OpenFOAM adapter's fsiCoupling entry without OpenFOAM's own
/// keys). docs/COUPLING.md lists the table.
OptionSchema couplingOptionSchema();

/// The structure's mode from validated options (`structureMode`).
StructureMode structureMode(const OptionValues& values);
/// equilibriumSteps and equilibriumStart of an equilibrium-mode option set (EquilibriumStructure).
EquilibriumOptions equilibriumOptions(const OptionValues& values);

/// The acceleration chosen by validated options (`acceleration` and its options).
std::unique_ptr<Acceleration> makeAcceleration(const OptionValues& values);
/// Scheme settings from validated options: kind, extrapolation, load relaxation, tolerance, maxIterations.
CouplingConfig couplingConfig(const OptionValues& values, double timeWindowSize, double endTime);

/// The schema as a Markdown table (key | type | default | valid | effect | description), for the docs.
std::string optionTable(const OptionSchema& schema);

}  // namespace fsi::coupling
