#include "core/release_memory.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace semchain {

void ReleaseFreeMemory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

}  // namespace semchain
