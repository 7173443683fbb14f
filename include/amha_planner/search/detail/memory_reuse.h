// Process-wide choices for freed memory: the search's large arrays (records, queue storage)
// returned to the kernel or kept for the next search in the process, and malloc's own large
// blocks mapped alone (the server and `amha plan`).
#pragma once

#include <cstddef>
#include <limits>

namespace amha {

/// With reuse on, a search's large arrays are not unmapped when it ends but kept, and the next
/// search takes them over with their pages already faulted in, as a long-lived planner that
/// keeps its buffers would. Benchmarks running thousands of searches use it (otherwise every
/// run pays the kernel's zeroing of its whole state space again: about 13 % of the CPU time on
/// Korf's 15-puzzles, docs/results/tiles.md). The price: up to `max_pooled_bytes` stay
/// resident between searches (a reused array gives back what it does not need, so searches
/// still use only the memory their caps count).
/// Off by default. Thread-safe; affects arrays freed after the call.
void setReuseFreedSearchMemory(
    bool reuse, std::size_t max_pooled_bytes = std::numeric_limits<std::size_t>::max());

/// Makes glibc map every block of `bytes` or more on its own and unmap it when it is freed
/// (mallopt M_MMAP_THRESHOLD, held there; it also fixes the trim threshold at its default). By
/// default glibc raises that threshold to the size of each large block it frees (up to 32 MiB),
/// and later large arrays come from the arenas, where what is freed stays resident: a replaced
/// map's tens of MB in a server, the kinematic table's and the grids' temporaries under a
/// search's peak. Process-wide; returns false if glibc refused (or it is not glibc).
bool mapLargeBlocksAlone(std::size_t bytes);

}  // namespace amha
