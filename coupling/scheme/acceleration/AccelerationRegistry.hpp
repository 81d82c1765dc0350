#pragma once
// The registry of the implicit scheme's accelerations: one entry per variant (coupling/scheme/acceleration/,
// one class per file), each with its name (the value of the option `acceleration`), a one-line description,
// its own options and a factory. The option table of a coupled run (CouplingOptions) takes the valid names,
// their "did you mean", their options and docs/COUPLING.md's table from here; makeAcceleration() builds the
// chosen one. Adding a variant: docs/ARCHITECTURE.md, "How to add a coupling acceleration".

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "coupling/scheme/Acceleration.hpp"
#include "coupling/scheme/CouplingOptions.hpp"

namespace fsi::coupling {

/// An acceleration of the implicit scheme: its name, a one-line description, its own options (conditions on
/// `acceleration` are added by couplingOptionSchema()) and a factory from validated options.
struct AccelerationEntry {
  std::string name;
  std::string description;
  std::vector<OptionSpec> options;
  std::function<std::unique_ptr<Acceleration>(const OptionValues&)> make;
};

/// Every registered acceleration, in registration order (the order of docs/COUPLING.md's option table).
const std::vector<AccelerationEntry>& accelerationEntries();
/// The entry called `name`, or null.
const AccelerationEntry* findAcceleration(const std::string& name);

}  // namespace fsi::coupling
