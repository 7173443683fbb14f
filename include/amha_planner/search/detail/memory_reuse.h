// Process-wide choice for the search's large arrays (records, queue storage): return freed
// ones to the kernel, or keep them for the next search in the process.
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

}  // namespace amha
