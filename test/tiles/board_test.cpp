// Boards, the solvability rule (against a BFS of the whole 3x3 space) and the generators.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <deque>
#include <numeric>
#include <unordered_set>

#include "amha_planner/tiles/board.h"
#include "amha_planner/tiles/instances.h"

namespace amha {
namespace tiles {
namespace {

std::uint64_t pack9(const std::vector<std::uint8_t>& t) {
  std::uint64_t v = 0;
  for (std::uint8_t x : t) v = v << 4 | x;
  return v;
}

TEST(Board, GoalIsSolvableAndWellFormed) {
  for (int n = kMinSize; n <= kMaxSize; ++n) {
    const Board g = goalBoard(n);
    EXPECT_EQ(boardError(g), "");
    EXPECT_TRUE(isSolvable(g));
    EXPECT_EQ(blankPosition(g), 0);
  }
}

TEST(Board, ErrorsNameTheProblem) {
  Board b = goalBoard(3);
  b.tiles[4] = 3;
  EXPECT_NE(boardError(b).find("appears twice"), std::string::npos);
  b.tiles[4] = 9;
  EXPECT_NE(boardError(b).find("out of range"), std::string::npos);
  b.tiles.pop_back();
  EXPECT_NE(boardError(b).find("expected 9 tiles"), std::string::npos);
  Board big = goalBoard(3);
  big.size = 10;
  EXPECT_NE(boardError(big).find("outside"), std::string::npos);
}

// The parity rule agrees with reachability on every one of the 9! boards of the 3x3 puzzle.
TEST(Board, ParityRuleMatchesBfsOn3x3) {
  const Board goal = goalBoard(3);
  std::unordered_set<std::uint64_t> seen{pack9(goal.tiles)};
  std::deque<Board> queue{goal};
  while (!queue.empty()) {
    const Board b = queue.front();
    queue.pop_front();
    const int p = blankPosition(b);
    for (int q : blankNeighbours(b)) {
      Board c = b;
      std::swap(c.tiles[p], c.tiles[q]);
      if (seen.insert(pack9(c.tiles)).second) queue.push_back(c);
    }
  }
  EXPECT_EQ(seen.size(), 181440u);  // 9! / 2
  Board b = goal;
  std::size_t solvable = 0;
  do {
    const bool reachable = seen.count(pack9(b.tiles)) > 0;
    ASSERT_EQ(isSolvable(b), reachable) << toString(b);
    solvable += reachable;
  } while (std::next_permutation(b.tiles.begin(), b.tiles.end()));
  EXPECT_EQ(solvable, 181440u);
}

// Even widths: walks from the goal stay solvable; swapping two tiles breaks solvability.
TEST(Board, ParityRuleOnEvenWidths) {
  for (int n : {4, 6, 8}) {
    for (int i = 0; i < 20; ++i) {
      Board b = randomWalkBoard(n, 50 + 37 * i, 7, static_cast<std::uint64_t>(i));
      ASSERT_TRUE(isSolvable(b)) << toString(b);
      // Swap the first two non-blank tiles.
      int a = -1, c = -1;
      for (int k = 0; k < n * n && c < 0; ++k) {
        if (b.tiles[k] == 0) continue;
        (a < 0 ? a : c) = k;
      }
      std::swap(b.tiles[a], b.tiles[c]);
      EXPECT_FALSE(isSolvable(b)) << toString(b);
    }
  }
}

TEST(Board, OneMoveApart) {
  const Board g = goalBoard(4);
  Board right = g;
  std::swap(right.tiles[0], right.tiles[1]);
  Board down = g;
  std::swap(down.tiles[0], down.tiles[4]);
  Board far = g;
  std::swap(far.tiles[0], far.tiles[2]);
  EXPECT_TRUE(isOneMoveApart(g, right));
  EXPECT_TRUE(isOneMoveApart(right, g));
  EXPECT_TRUE(isOneMoveApart(g, down));
  EXPECT_FALSE(isOneMoveApart(g, far));
  EXPECT_FALSE(isOneMoveApart(g, g));
  // Wrap-around is not a move: blank at the end of row 0 and the start of row 1.
  Board wrap = goalBoard(4);
  std::swap(wrap.tiles[0], wrap.tiles[3]);  // blank at position 3
  Board wrapped = wrap;
  std::swap(wrapped.tiles[3], wrapped.tiles[4]);
  EXPECT_FALSE(isOneMoveApart(wrap, wrapped));
}

TEST(Generators, RandomBoardsAreSolvableAndReproducible) {
  for (int n = kMinSize; n <= kMaxSize; ++n) {
    for (std::uint64_t i = 0; i < 10; ++i) {
      const Board b = randomSolvableBoard(n, 42, i);
      ASSERT_EQ(boardError(b), "");
      EXPECT_TRUE(isSolvable(b));
      EXPECT_EQ(b, randomSolvableBoard(n, 42, i));
      EXPECT_NE(b, randomSolvableBoard(n, 43, i));
      EXPECT_NE(b, randomSolvableBoard(n, 42, i + 1));
    }
  }
  // Instance i does not depend on how many are generated.
  const auto five = generateInstances(7, 5, 1);
  const auto three = generateInstances(7, 3, 1);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(five[i].start, three[i].start);
  EXPECT_EQ(five[2].id, "rand7-s1-2");
  EXPECT_FALSE(five[2].optimal.has_value());
}

// Uniformity: on solvable 3x3 boards every tile is equally likely at every position
// (20160 of the 181440 solvable boards each). Chi-square over the 81 cells, 18000 samples.
TEST(Generators, RandomBoardsAreRoughlyUniform) {
  const int samples = 18000;
  std::vector<int> count(81, 0);
  std::unordered_set<std::uint64_t> distinct;
  for (int i = 0; i < samples; ++i) {
    const Board b = randomSolvableBoard(3, 2024, static_cast<std::uint64_t>(i));
    for (int p = 0; p < 9; ++p) ++count[p * 9 + b.tiles[p]];
    distinct.insert(pack9(b.tiles));
  }
  const double expected = samples / 9.0;
  double chi2 = 0;
  for (int c : count) chi2 += (c - expected) * (c - expected) / expected;
  // 64 degrees of freedom (8 x 8): the 99.99th percentile is about 117.
  EXPECT_LT(chi2, 117.0) << "chi-square " << chi2;
  // Birthday check: 18000 draws from 181440 boards give about 17170 distinct ones.
  EXPECT_GT(distinct.size(), 16900u);
  EXPECT_LT(distinct.size(), 17400u);
}

TEST(Generators, RandomWalks) {
  EXPECT_EQ(randomWalkBoard(5, 0, 1, 0), goalBoard(5));
  // One move: the blank went right or down.
  const Board one = randomWalkBoard(5, 1, 1, 0);
  EXPECT_TRUE(isOneMoveApart(goalBoard(5), one));
  for (int n = kMinSize; n <= kMaxSize; ++n) {
    const Board b = randomWalkBoard(n, 200, 9, 3);
    EXPECT_TRUE(isSolvable(b));
    EXPECT_EQ(b, randomWalkBoard(n, 200, 9, 3));
  }
  const auto w = generateInstances(4, 2, 5, 30);
  EXPECT_EQ(w[1].id, "walk4-L30-s5-1");
  EXPECT_EQ(w[1].start, randomWalkBoard(4, 30, 5, 1));
}

}  // namespace
}  // namespace tiles
}  // namespace amha
