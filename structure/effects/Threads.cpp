#include "structure/effects/Threads.hpp"

namespace fsi::structure {

bool threadsAvailable() {
#ifdef FSI_HAVE_OPENMP
  return true;
#else
  return false;
#endif
}

}  // namespace fsi::structure
