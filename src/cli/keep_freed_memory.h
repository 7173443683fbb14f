// Process-wide allocator tuning: for benchmark commands that run many searches in a row, and
// for `amha plan`, which runs one.
#pragma once

#include <cstddef>

namespace amha {
namespace cli {

/// Keeps freed memory mapped and reuses it (the search's pool of large arrays; for the rest,
/// glibc without mmap for large blocks and without trimming), so that a search run after
/// another one reuses pages the kernel has already zeroed and faulted in, as it would in a
/// long-lived planner that keeps its buffers. Without it every run of `amha tiles` pays the
/// page faults of its whole state space again: about 13 % of the CPU time on Korf's
/// 15-puzzles (docs/results/tiles.md). Call before the first large allocation. Between runs
/// the pool keeps at most `max_pooled_bytes`; the heap keeps its peak.
void keepFreedMemoryMapped(std::size_t max_pooled_bytes);

/// The opposite, for a command that plans once: every block of 128 KiB or more is mapped on its
/// own and unmapped when freed (mapLargeBlocksAlone at glibc's initial threshold, held there).
/// By default glibc raises that threshold to the size of each large block it frees (up to
/// 32 MiB), so after the kinematic table's and the grids' temporaries are freed the planner's
/// later arrays come from the arenas, where what is freed stays resident under the search's
/// peak: 1-2 MB of `amha plan`'s peak RSS on Willow Garage at 5 cm (docs/results/smac.md).
/// Returns false if glibc refused. Call before the first large allocation.
bool unmapFreedLargeBlocks();

}  // namespace cli
}  // namespace amha
