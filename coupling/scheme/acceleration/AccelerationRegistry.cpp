#include "coupling/scheme/acceleration/AccelerationRegistry.hpp"

#include "coupling/scheme/acceleration/Aitken.hpp"
#include "coupling/scheme/acceleration/ConstantRelaxation.hpp"
#include "coupling/scheme/acceleration/IqnIls.hpp"

namespace fsi::coupling {

const std::vector<AccelerationEntry>& accelerationEntries() {
  // One line per acceleration. Explicit rather than self-registering objects: a static library drops an
  // object file nothing refers to, and with it its registration.
  static const std::vector<AccelerationEntry> entries{
      constantRelaxationEntry(),
      aitkenEntry(),
      iqnIlsEntry(),
  };
  return entries;
}

const AccelerationEntry* findAcceleration(const std::string& name) {
  for (const AccelerationEntry& e : accelerationEntries())
    if (e.name == name) return &e;
  return nullptr;
}

}  // namespace fsi::coupling
