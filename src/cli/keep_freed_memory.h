// Process-wide allocator tuning for benchmark commands that run many searches in a row.
#pragma once

namespace amha {
namespace cli {

/// Keeps freed memory mapped and reuses it (the search's pool of large arrays; for the rest,
/// glibc without mmap for large blocks and without trimming), so that a search run after
/// another one reuses pages the kernel has already zeroed and faulted in, as it would in a
/// long-lived planner that keeps its buffers. Without it every run of `amha tiles` pays the
/// page faults of its whole state space again: about 13 % of the CPU time on Korf's
/// 15-puzzles (docs/results/tiles.md). Call before the first large allocation. The process's
/// resident memory then stays at the largest run's peak.
void keepFreedMemoryMapped();

}  // namespace cli
}  // namespace amha
