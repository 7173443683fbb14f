// The sliding-tile heuristics: Manhattan distance (MD), linear conflict (LC), misplaced tiles
// (MT), the anchor MD + LC (admissible and consistent), and the paper's inadmissible
// heuristics a*MD + b*LC + c*MT with random weights.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "amha_planner/tiles/board.h"

namespace amha {
namespace tiles {

/// The three terms every tile heuristic here is built from, computed once per state.
struct HeuristicTerms {
  int md = 0;  ///< sum over tiles (not the blank) of |row - goal row| + |col - goal col|
  int lc = 0;  ///< linear conflict: 2 * sum over rows and columns of the minimum number of
               ///< tiles to remove from the line so that no two of its tiles that belong in
               ///< it are in reverse order (= tiles in goal line - longest increasing run)
  int mt = 0;  ///< tiles (not the blank) away from their goal position
};

int manhattanDistance(const Board& b);
int linearConflict(const Board& b);
int misplacedTiles(const Board& b);
HeuristicTerms heuristicTerms(const Board& b);

/// Minimum removals for one line of a board given as tiles[pos] (row-major, N x N):
/// `row` selects row `index`, otherwise column `index`. LC is 2 * the sum over all lines.
int lineConflictRemovals(const std::uint8_t* tiles, int size, bool row, int index);

/// Weights of one inadmissible heuristic h = md * MD + lc * LC + mt * MT.
struct TermWeights {
  double md = 1.0, lc = 1.0, mt = 1.0;
};

/// `count` weight triples drawn uniformly from [lo, hi] (the paper: [1, 5]) from
/// std::mt19937(seed). Computed as lo + (hi - lo) * u with u = rng() / 2^32, so the values are
/// the same with every standard library (std::uniform_real_distribution is not portable).
std::vector<TermWeights> randomTermWeights(std::size_t count, std::uint32_t seed, double lo = 1.0,
                                           double hi = 5.0);

/// The anchor MD + LC.
inline std::uint32_t anchorValue(const HeuristicTerms& t) {
  return static_cast<std::uint32_t>(t.md + t.lc);
}

/// An inadmissible value, rounded to the nearest integer (the search stores integers).
/// Inline and without std::lround: it runs for every heuristic of every new state.
inline std::uint32_t weightedValue(const HeuristicTerms& t, const TermWeights& w) {
  return static_cast<std::uint32_t>(w.md * t.md + w.lc * t.lc + w.mt * t.mt + 0.5);
}

}  // namespace tiles
}  // namespace amha
