#include "amha_planner/tiles/heuristics.h"

#include <cmath>
#include <cstdlib>
#include <random>

namespace amha {
namespace tiles {

int manhattanDistance(const Board& b) {
  const int n = b.size;
  int md = 0;
  for (int p = 0; p < n * n; ++p) {
    const int t = b.tiles[p];
    if (t == 0) continue;
    md += std::abs(p / n - t / n) + std::abs(p % n - t % n);
  }
  return md;
}

int lineConflictRemovals(const std::uint8_t* tiles, int n, bool row, int index) {
  // The tiles of the line that belong in it, in line order, form a sequence of distinct goal
  // offsets; the fewest removals leaving no reversed pair is its length minus its longest
  // increasing subsequence. Patience sorting with the pile tops as a bit set: each value
  // replaces the smallest top above it (or starts a pile); the pile count is the LIS length.
  unsigned tops = 0;
  int in_line = 0;
  for (int k = 0; k < n; ++k) {
    const int p = row ? index * n + k : k * n + index;
    const int t = tiles[p];
    if (t == 0) continue;
    const int goal_line = row ? t / n : t % n;
    if (goal_line != index) continue;
    const unsigned v = static_cast<unsigned>(row ? t % n : t / n);
    ++in_line;
    const unsigned above = tops & ~((2u << v) - 1u);
    tops ^= above & (0u - above);  // drop the lowest top above v (no-op if none)
    tops |= 1u << v;
  }
  return in_line - __builtin_popcount(tops);
}

int linearConflict(const Board& b) {
  int removals = 0;
  for (int i = 0; i < b.size; ++i) {
    removals += lineConflictRemovals(b.tiles.data(), b.size, true, i);
    removals += lineConflictRemovals(b.tiles.data(), b.size, false, i);
  }
  return 2 * removals;
}

int misplacedTiles(const Board& b) {
  int mt = 0;
  for (std::size_t p = 0; p < b.tiles.size(); ++p) {
    if (b.tiles[p] != 0 && b.tiles[p] != p) ++mt;
  }
  return mt;
}

HeuristicTerms heuristicTerms(const Board& b) {
  return HeuristicTerms{manhattanDistance(b), linearConflict(b), misplacedTiles(b)};
}

std::vector<TermWeights> randomTermWeights(std::size_t count, std::uint32_t seed, double lo,
                                           double hi) {
  std::mt19937 rng(seed);
  auto draw = [&] { return lo + (hi - lo) * (static_cast<double>(rng()) / 4294967296.0); };
  std::vector<TermWeights> out(count);
  for (TermWeights& w : out) {
    w.md = draw();
    w.lc = draw();
    w.mt = draw();
  }
  return out;
}

std::uint32_t weightedValue(const HeuristicTerms& t, const TermWeights& w) {
  const double v = w.md * t.md + w.lc * t.lc + w.mt * t.mt;
  return static_cast<std::uint32_t>(std::lround(v));
}

}  // namespace tiles
}  // namespace amha
