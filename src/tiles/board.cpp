#include "amha_planner/tiles/board.h"

#include <cstdlib>
#include <sstream>

namespace amha {
namespace tiles {

Board goalBoard(int size) {
  Board b;
  b.size = size;
  b.tiles.resize(static_cast<std::size_t>(size * size));
  for (int k = 0; k < size * size; ++k) b.tiles[k] = static_cast<std::uint8_t>(k);
  return b;
}

int blankPosition(const Board& b) {
  for (std::size_t k = 0; k < b.tiles.size(); ++k) {
    if (b.tiles[k] == 0) return static_cast<int>(k);
  }
  return -1;
}

std::string boardError(const Board& b) {
  if (b.size < kMinSize || b.size > kMaxSize) {
    return "board size " + std::to_string(b.size) + " is outside " + std::to_string(kMinSize) +
           ".." + std::to_string(kMaxSize);
  }
  const std::size_t n = static_cast<std::size_t>(b.size * b.size);
  if (b.tiles.size() != n) {
    return "expected " + std::to_string(n) + " tiles for a " + std::to_string(b.size) + "x" +
           std::to_string(b.size) + " board, got " + std::to_string(b.tiles.size());
  }
  std::vector<int> seen_at(n, -1);
  for (std::size_t k = 0; k < n; ++k) {
    const int t = b.tiles[k];
    if (t >= static_cast<int>(n)) {
      return "tile " + std::to_string(t) + " at position " + std::to_string(k) +
             " is out of range 0.." + std::to_string(n - 1);
    }
    if (seen_at[t] >= 0) {
      return "tile " + std::to_string(t) + " appears twice (positions " +
             std::to_string(seen_at[t]) + " and " + std::to_string(k) + ")";
    }
    seen_at[t] = static_cast<int>(k);
  }
  return "";
}

long inversions(const Board& b) {
  // O(n^2) over at most 80 tiles: fine for validation and generation.
  long inv = 0;
  const std::size_t n = b.tiles.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (b.tiles[i] == 0) continue;
    for (std::size_t j = i + 1; j < n; ++j) {
      if (b.tiles[j] != 0 && b.tiles[j] < b.tiles[i]) ++inv;
    }
  }
  return inv;
}

bool isSolvable(const Board& b) {
  const long inv = inversions(b);
  if (b.size % 2 == 1) return inv % 2 == 0;
  const int blank_row = blankPosition(b) / b.size;
  return (inv + blank_row) % 2 == 0;
}

std::vector<int> blankNeighbours(const Board& b) {
  const int p = blankPosition(b), n = b.size;
  const int r = p / n, c = p % n;
  std::vector<int> out;
  if (r > 0) out.push_back(p - n);
  if (r < n - 1) out.push_back(p + n);
  if (c > 0) out.push_back(p - 1);
  if (c < n - 1) out.push_back(p + 1);
  return out;
}

bool isOneMoveApart(const Board& b, const Board& c) {
  if (b.size != c.size || b.tiles.size() != c.tiles.size()) return false;
  const int p = blankPosition(b);
  for (int q : blankNeighbours(b)) {
    if (c.tiles[q] != 0 || c.tiles[p] != b.tiles[q]) continue;
    bool same_elsewhere = true;
    for (std::size_t k = 0; k < b.tiles.size(); ++k) {
      if (static_cast<int>(k) != p && static_cast<int>(k) != q && b.tiles[k] != c.tiles[k]) {
        same_elsewhere = false;
        break;
      }
    }
    if (same_elsewhere) return true;
  }
  return false;
}

std::string toString(const Board& b) {
  std::ostringstream out;
  for (std::size_t k = 0; k < b.tiles.size(); ++k) {
    if (k > 0) out << (b.size > 0 && k % b.size == 0 ? " / " : " ");
    out << static_cast<int>(b.tiles[k]);
  }
  return out.str();
}

}  // namespace tiles
}  // namespace amha
