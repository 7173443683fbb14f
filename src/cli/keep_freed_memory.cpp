#include "keep_freed_memory.h"

#include <malloc.h>


namespace amha {
namespace cli {

void keepFreedMemoryMapped() {
  // Blocks above M_MMAP_THRESHOLD (at most 32 MiB) would be mmap'ed and unmapped on free;
  // with M_MMAP_MAX = 0 they come from the heap, whose freed top is never trimmed.
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, -1);  // -1: never trim
}

}  // namespace cli
}  // namespace amha
