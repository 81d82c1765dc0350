// The registry of the element kinds' scene readers: one line per kind (its reader in its own file here).
#include "structure/scene/kinds/KindReaders.hpp"

namespace fsi::structure {

KindReader membraneReader();
KindReader cableReader();
KindReader pointMassReader();
KindReader barReader();

const std::vector<KindReader>& kindReaders() {
  static const std::vector<KindReader> readers{membraneReader(), cableReader(), pointMassReader(),
                                               barReader()};
  return readers;
}

}  // namespace fsi::structure
