// MD, LC and MT: hand-checked values, LC against a brute-force minimum, the anchor's
// admissibility against exact 3x3 distances, consistency on random edges, and the weights.
#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <unordered_map>

#include "amha_planner/tiles/heuristics.h"
#include "amha_planner/tiles/instances.h"

namespace amha {
namespace tiles {
namespace {

Board make(int n, std::vector<int> t) {
  Board b;
  b.size = n;
  for (int x : t) b.tiles.push_back(static_cast<std::uint8_t>(x));
  return b;
}

TEST(Heuristics, HandCheckedValues) {
  const Board g = goalBoard(3);
  EXPECT_EQ(heuristicTerms(g).md, 0);
  EXPECT_EQ(heuristicTerms(g).lc, 0);
  EXPECT_EQ(heuristicTerms(g).mt, 0);
  // Row 1 reversed (5 4 3): three tiles of the row in it, longest increasing run 1 -> remove 2.
  const Board r = make(3, {0, 1, 2, 5, 4, 3, 6, 7, 8});
  EXPECT_EQ(manhattanDistance(r), 4);
  EXPECT_EQ(linearConflict(r), 4);
  EXPECT_EQ(misplacedTiles(r), 2);
  // Column conflict: tiles 1 and 4 swapped in column 1 (goal column 1 holds 1, 4, 7).
  const Board c = make(3, {0, 4, 2, 3, 1, 5, 6, 7, 8});
  EXPECT_EQ(manhattanDistance(c), 2);
  EXPECT_EQ(linearConflict(c), 2);
  EXPECT_EQ(misplacedTiles(c), 2);
  // The blank never counts: blank moved right once.
  const Board m = make(3, {1, 0, 2, 3, 4, 5, 6, 7, 8});
  EXPECT_EQ(manhattanDistance(m), 1);
  EXPECT_EQ(linearConflict(m), 0);
  EXPECT_EQ(misplacedTiles(m), 1);
  // Korf's instance 1 (md 41 as listed in the file).
  const Board k1 = make(4, {14, 13, 15, 7, 11, 12, 9, 5, 6, 0, 2, 1, 4, 8, 10, 3});
  EXPECT_EQ(manhattanDistance(k1), 41);
}

// Brute force: the fewest tiles to drop from a line so that the rest is in goal order.
int bruteRemovals(const Board& b, bool row, int index) {
  const int n = b.size;
  std::vector<int> vals;
  for (int k = 0; k < n; ++k) {
    const int t = b.tiles[row ? index * n + k : k * n + index];
    if (t != 0 && (row ? t / n : t % n) == index) vals.push_back(row ? t % n : t / n);
  }
  const int m = static_cast<int>(vals.size());
  int best = m;
  for (int mask = 0; mask < (1 << m); ++mask) {
    int last = -1;
    bool ok = true;
    for (int i = 0; i < m && ok; ++i) {
      if (!(mask >> i & 1)) continue;
      ok = vals[i] > last;
      last = vals[i];
    }
    if (ok) best = std::min(best, m - __builtin_popcount(mask));
  }
  return best;
}

TEST(Heuristics, LineConflictMatchesBruteForce) {
  for (int n = kMinSize; n <= kMaxSize; ++n) {
    for (int i = 0; i < 200; ++i) {
      // Random boards have few tiles in their goal lines; walks from the goal have many.
      const Board b =
          (i % 2 == 0) ? randomSolvableBoard(n, 5, i) : randomWalkBoard(n, 10 + i, 5, i);
      int total = 0;
      for (int line = 0; line < n; ++line) {
        for (bool row : {true, false}) {
          const int got = lineConflictRemovals(b.tiles.data(), n, row, line);
          ASSERT_EQ(got, bruteRemovals(b, row, line)) << toString(b);
          total += got;
        }
      }
      EXPECT_EQ(linearConflict(b), 2 * total);
    }
  }
}

// The anchor never exceeds the exact distance on any of the 181440 solvable 3x3 boards.
TEST(Heuristics, AnchorAdmissibleOnAll3x3Boards) {
  auto key = [](const Board& b) {
    std::uint64_t v = 0;
    for (std::uint8_t x : b.tiles) v = v << 4 | x;
    return v;
  };
  std::unordered_map<std::uint64_t, int> dist{{key(goalBoard(3)), 0}};
  std::deque<Board> queue{goalBoard(3)};
  int tight = 0;
  while (!queue.empty()) {
    const Board b = queue.front();
    queue.pop_front();
    const int d = dist[key(b)];
    const HeuristicTerms t = heuristicTerms(b);
    ASSERT_LE(static_cast<int>(anchorValue(t)), d) << toString(b);
    tight += static_cast<int>(anchorValue(t)) == d;
    const int p = blankPosition(b);
    for (int q : blankNeighbours(b)) {
      Board c = b;
      std::swap(c.tiles[p], c.tiles[q]);
      if (dist.emplace(key(c), d + 1).second) queue.push_back(c);
    }
  }
  EXPECT_EQ(dist.size(), 181440u);
  EXPECT_GT(tight, 1000);  // and it is informative, not trivially 0
}

// Consistency: across every edge the anchor changes by at most the edge cost (1), and MD
// changes by exactly 1 and MT by at most 1.
TEST(Heuristics, AnchorConsistentOnRandomEdges) {
  for (int n = kMinSize; n <= kMaxSize; ++n) {
    for (int i = 0; i < 300; ++i) {
      const Board b =
          (i % 3 == 0) ? randomSolvableBoard(n, 11, i) : randomWalkBoard(n, 3 * i, 11, i);
      const HeuristicTerms tb = heuristicTerms(b);
      const int p = blankPosition(b);
      for (int q : blankNeighbours(b)) {
        Board c = b;
        std::swap(c.tiles[p], c.tiles[q]);
        const HeuristicTerms tc = heuristicTerms(c);
        ASSERT_LE(std::abs(static_cast<int>(anchorValue(tb)) - static_cast<int>(anchorValue(tc))),
                  1)
            << toString(b) << " -> " << toString(c);
        ASSERT_EQ(std::abs(tb.md - tc.md), 1);
        ASSERT_LE(std::abs(tb.mt - tc.mt), 1);
      }
    }
  }
}

TEST(Heuristics, RandomWeightsInRangeAndReproducible) {
  const auto w = randomTermWeights(4, 1);
  ASSERT_EQ(w.size(), 4u);
  for (const TermWeights& x : w) {
    for (double v : {x.md, x.lc, x.mt}) {
      EXPECT_GE(v, 1.0);
      EXPECT_LT(v, 5.0);
    }
  }
  const auto again = randomTermWeights(4, 1);
  const auto other = randomTermWeights(4, 2);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(w[i].md, again[i].md);
    EXPECT_NE(w[i].md, other[i].md);
  }
  // More heuristics extend the list: the first four stay the same.
  const auto six = randomTermWeights(6, 1);
  EXPECT_EQ(six[3].mt, w[3].mt);
  // Spread over many draws covers the range.
  double lo = 5, hi = 1;
  for (const TermWeights& x : randomTermWeights(1000, 3)) {
    lo = std::min(lo, x.md);
    hi = std::max(hi, x.md);
  }
  EXPECT_LT(lo, 1.05);
  EXPECT_GT(hi, 4.95);
  EXPECT_EQ(weightedValue(HeuristicTerms{10, 4, 3}, TermWeights{1.5, 2.0, 1.0}), 26u);
  EXPECT_EQ(weightedValue(HeuristicTerms{0, 0, 0}, w[0]), 0u);
}

}  // namespace
}  // namespace tiles
}  // namespace amha
