#include "keep_freed_memory.h"

#include <malloc.h>

#include "amha_planner/search/detail/memory_reuse.h"

namespace amha {
namespace cli {

void keepFreedMemoryMapped(std::size_t max_pooled_bytes) {
  // The search's large arrays have their own mappings: keep them in the search's pool.
  setReuseFreedSearchMemory(true, max_pooled_bytes);
  // Everything else (e.g. the tile domain's boards and table): blocks above M_MMAP_THRESHOLD
  // (at most 32 MiB) would be mmap'ed and unmapped on free; with M_MMAP_MAX = 0 they come
  // from the heap, whose freed top is never trimmed. None of the large ones grows by realloc,
  // so none is ever copied on the heap.
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, -1);  // -1: never trim
}

bool unmapFreedLargeBlocks() {
  constexpr std::size_t kThresholdBytes = 128 * 1024;  // glibc's own initial threshold
  return mapLargeBlocksAlone(kThresholdBytes);
}

}  // namespace cli
}  // namespace amha
