// Process-wide allocator tuning for benchmark commands that run many searches in a row.
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

}  // namespace cli
}  // namespace amha
