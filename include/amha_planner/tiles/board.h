// Sliding-tile boards (N x N, N = 3..9): the representation shared by instances, heuristics
// and the search domain. Convention (Korf's): tiles[k] is the tile at board position k
// (row-major), 0 is the blank, and the goal is 0 1 2 ... N*N-1 (blank top-left).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace amha {
namespace tiles {

constexpr int kMinSize = 3;
constexpr int kMaxSize = 9;

struct Board {
  int size = 0;                     ///< N: the board is N x N
  std::vector<std::uint8_t> tiles;  ///< N*N entries, a permutation of 0 .. N*N-1

  bool operator==(const Board& o) const { return size == o.size && tiles == o.tiles; }
  bool operator!=(const Board& o) const { return !(*this == o); }
};

/// The goal board 0 1 2 ... N*N-1.
Board goalBoard(int size);

/// Position of the blank (tile 0).
int blankPosition(const Board& b);

/// Empty if `b` is a well-formed board (size in range, N*N tiles, a permutation of
/// 0..N*N-1); otherwise a one-line description of the first problem found.
std::string boardError(const Board& b);

/// Whether the goal is reachable from `b` (a well-formed board). With the blank top-left goal:
/// odd N: the number of inversions among the tiles 1..N*N-1 (row-major) is even;
/// even N: inversions + the blank's row (0 = top) is even. (A horizontal move keeps both the
/// inversion count and the row; a vertical move changes the inversions by N-1 and the row by 1.)
bool isSolvable(const Board& b);

/// Number of inversions among the non-blank tiles in row-major order.
long inversions(const Board& b);

/// The blank's legal moves: positions the blank can swap with (2 to 4 of them).
std::vector<int> blankNeighbours(const Board& b);

/// Whether `b` and `c` differ by exactly one legal move (blank swapped with a neighbour).
bool isOneMoveApart(const Board& b, const Board& c);

/// "1 2 3 / 4 0 5 / ..." style one-line text, for messages.
std::string toString(const Board& b);

}  // namespace tiles
}  // namespace amha
