// Linear conflict of one line, for a board size known at compile time (the division and
// modulo by N become multiplications), shared by heuristics.cpp and the search domain.
#pragma once

#include <cstdint>

namespace amha {
namespace tiles {
namespace detail {

struct PopcountTable {
  std::uint8_t bits[512];
  constexpr PopcountTable() : bits() {
    for (int i = 0; i < 512; ++i) bits[i] = static_cast<std::uint8_t>((i & 1) + bits[i / 2]);
  }
};
// A table: __builtin_popcount is a libgcc call when the target has no popcnt instruction.
inline constexpr PopcountTable kPopcount9{};

/// Minimum removals for row `index` (row = true) or column `index` of an N x N board given as
/// tiles[position]. The tiles of the line that belong in it, in line order, form a sequence of
/// distinct goal offsets; the fewest removals leaving no reversed pair is its length minus its
/// longest increasing subsequence. Patience sorting with the pile tops as a bit set: each value
/// replaces the smallest top above it (or starts a new pile); the pile count is the LIS length.
template <int N>
inline int lineRemovals(const std::uint8_t* tiles, bool row, int index) {
  unsigned tops = 0;
  int in_line = 0;
  for (int k = 0; k < N; ++k) {
    const int t = tiles[row ? index * N + k : k * N + index];
    if (t == 0) continue;
    if ((row ? t / N : t % N) != index) continue;
    const unsigned v = static_cast<unsigned>(row ? t % N : t / N);
    ++in_line;
    const unsigned above = tops & ~((2u << v) - 1u);
    tops ^= above & (0u - above);  // drop the lowest top above v (no-op if none)
    tops |= 1u << v;
  }
  return in_line - kPopcount9.bits[tops];
}

/// Change in lineRemovals when tile `t` (whose goal line is this line) is added at offset
/// `at` of the line, where the line otherwise holds the values get(k) (k != at; the cell at
/// `at` is ignored). Adding one tile raises the in-line count by 1 and the longest increasing
/// subsequence by 0 or 1, so the result is 0 or 1. One pass computes both sequences.
/// `get(k)` returns the tile at offset k of the line.
template <int N, typename Get>
inline int lineRemovalsAddedTile(Get&& get, bool row, int index, int at, int t) {
  unsigned with = 0, without = 0;
  for (int k = 0; k < N; ++k) {
    int v;
    if (k == at) {
      v = row ? t % N : t / N;
      const unsigned above = with & ~((2u << v) - 1u);
      with ^= above & (0u - above);
      with |= 1u << v;
      continue;
    }
    const int c = get(k);
    if (c == 0 || (row ? c / N : c % N) != index) continue;
    v = row ? c % N : c / N;
    unsigned above = with & ~((2u << v) - 1u);
    with ^= above & (0u - above);
    with |= 1u << v;
    above = without & ~((2u << v) - 1u);
    without ^= above & (0u - above);
    without |= 1u << v;
  }
  return 1 - (kPopcount9.bits[with] - kPopcount9.bits[without]);
}

}  // namespace detail
}  // namespace tiles
}  // namespace amha
