// Returning freed heap memory to the kernel (see freed_memory.h).
#include "amha_planner/ros/freed_memory.h"

#include <malloc.h>

#include <algorithm>

namespace amha_planner {

FreedMemory FreedMemoryReleaser::releaseIfMuchFreed() {
  std::lock_guard<std::mutex> lock(mutex_);
  FreedMemory out;
  out.free_bytes = mallinfo2().fordblks;
  least_free_ = std::min(least_free_, out.free_bytes);
  if (out.free_bytes > least_free_ + min_bytes_) {
    malloc_trim(0);  // every arena, not only the main heap's top
    out.trimmed = true;
    least_free_ = mallinfo2().fordblks;
  }
  return out;
}

}  // namespace amha_planner
