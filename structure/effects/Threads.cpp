#include "structure/effects/Threads.hpp"

#ifdef FSI_HAVE_OPENMP
#include <omp.h>
#endif

namespace fsi::structure {

bool threadsAvailable() {
#ifdef FSI_HAVE_OPENMP
  return true;
#else
  return false;
#endif
}

OneThreadScope::OneThreadScope() {
#ifdef FSI_HAVE_OPENMP
  saved_ = omp_get_max_active_levels();
  omp_set_max_active_levels(0);
#endif
}

OneThreadScope::~OneThreadScope() {
#ifdef FSI_HAVE_OPENMP
  omp_set_max_active_levels(saved_);
#endif
}

}  // namespace fsi::structure
