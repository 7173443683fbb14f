// Returning freed heap memory to the kernel. By default glibc raises its mmap threshold after
// each large block it frees (up to 32 MiB): from then on the arrays of a map of millions of
// cells are carved from the arenas, which keep what is freed for reuse, so tens of MB of a
// replaced 4000 x 4000 map stay resident for good although the heap in use is back to its usual
// size (docs/results/robustness.md, "Memory after huge maps"). The server therefore maps large
// blocks alone (amha::mapLargeBlocksAlone, in the library's memory_reuse.h, shared with
// `amha plan`) and, with the releaser here, trims what smaller blocks leave between live ones.
// ROS-free so that it can be tested.
#pragma once

#include <cstddef>
#include <mutex>

namespace amha_planner {

struct FreedMemory {
  std::size_t free_bytes = 0;  ///< free bytes the arenas held (mallinfo2's fordblks)
  bool trimmed = false;        ///< whether malloc_trim ran
};

/// Gives the pages of the arenas' free chunks back to the kernel (malloc_trim) once more than
/// `min_bytes` have been freed since it last did: what smaller blocks leave scattered between
/// live ones. Free chunks stay in the arenas' books after a trim (only their pages go), so
/// "freed since" is the growth of the free bytes over the least seen since the last trim.
/// Thread-safe; a check walks the arenas' free lists (cheap next to a build or a search).
class FreedMemoryReleaser {
 public:
  explicit FreedMemoryReleaser(std::size_t min_bytes) : min_bytes_(min_bytes) {}
  FreedMemory releaseIfMuchFreed();

 private:
  const std::size_t min_bytes_;
  std::mutex mutex_;
  std::size_t least_free_ = 0;  ///< the least free bytes seen since the last trim
};

}  // namespace amha_planner
