#include "amha_planner/tiles/heuristics.h"

#include <cmath>
#include <cstdlib>
#include <random>

#include "line_conflict.h"

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
  switch (n) {
    case 3:
      return detail::lineRemovals<3>(tiles, row, index);
    case 4:
      return detail::lineRemovals<4>(tiles, row, index);
    case 5:
      return detail::lineRemovals<5>(tiles, row, index);
    case 6:
      return detail::lineRemovals<6>(tiles, row, index);
    case 7:
      return detail::lineRemovals<7>(tiles, row, index);
    case 8:
      return detail::lineRemovals<8>(tiles, row, index);
    case 9:
      return detail::lineRemovals<9>(tiles, row, index);
    default:
      return 0;
  }
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

}  // namespace tiles
}  // namespace amha
