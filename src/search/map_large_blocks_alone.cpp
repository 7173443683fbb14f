// malloc's mmap threshold (see memory_reuse.h).
#include <malloc.h>

#include <climits>

#include "amha_planner/search/detail/memory_reuse.h"

namespace amha {

bool mapLargeBlocksAlone(std::size_t bytes) {
  if (bytes > static_cast<std::size_t>(INT_MAX)) return false;
  return mallopt(M_MMAP_THRESHOLD, static_cast<int>(bytes)) == 1;
}

}  // namespace amha
