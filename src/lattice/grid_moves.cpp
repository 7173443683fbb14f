#include "amha_planner/lattice/detail/grid_moves.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace amha {
namespace lattice {

std::vector<GridMove> gridMoves(int connectivity) {
  std::vector<GridMove> moves;
  auto add = [&](int dx, int dy) {
    GridMove m;
    m.dx = dx;
    m.dy = dy;
    m.length = std::hypot(dx, dy);
    rasterizeSegment({0.5, 0.5}, {dx + 0.5, dy + 0.5}, m.required);
    uniqueCells(m.required);
    m.either_side = std::abs(dx) == 1 && std::abs(dy) == 1;
    moves.push_back(std::move(m));
  };
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      if (dx != 0 || dy != 0) add(dx, dy);
    }
  }
  if (connectivity == 16) {
    const int k[8][2] = {{2, 1}, {1, 2}, {-1, 2}, {-2, 1}, {-2, -1}, {-1, -2}, {1, -2}, {2, -1}};
    for (const auto& d : k) add(d[0], d[1]);
  }
  return moves;
}

double walkLength(const std::vector<CellOffset>& cells, CellOffset to,
                  const std::vector<GridMove>& moves) {
  std::vector<CellOffset> cs = cells;
  uniqueCells(cs);
  auto index = [&](CellOffset c) {
    const auto it = std::lower_bound(cs.begin(), cs.end(), c);
    return it != cs.end() && *it == c ? static_cast<std::size_t>(it - cs.begin()) : cs.size();
  };
  const std::size_t m = cs.size();
  const std::size_t src = index({0, 0}), dst = index(to);
  if (src == m || dst == m) return std::numeric_limits<double>::infinity();
  // Dijkstra with a heap: a long primitive has thousands of cells.
  std::vector<double> d(m, std::numeric_limits<double>::infinity());
  using Item = std::pair<double, std::size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  d[src] = 0.0;
  queue.push({0.0, src});
  while (!queue.empty()) {
    const Item top = queue.top();
    queue.pop();
    const std::size_t u = top.second;
    if (top.first != d[u]) continue;
    if (u == dst) return d[u];
    for (const GridMove& mv : moves) {
      // Ends present, and every other required cell (or, for either_side, at least one).
      int sides = 0, sides_present = 0;
      bool ok = true;
      for (const CellOffset& r : mv.required) {
        const bool end = (r.dx == 0 && r.dy == 0) || (r.dx == mv.dx && r.dy == mv.dy);
        const bool present = index({cs[u].dx + r.dx, cs[u].dy + r.dy}) != m;
        if (end || !mv.either_side) {
          ok = ok && present;
        } else {
          ++sides;
          sides_present += present;
        }
      }
      if (!ok || (sides > 0 && sides_present == 0)) continue;
      const std::size_t v = index({cs[u].dx + mv.dx, cs[u].dy + mv.dy});
      if (v < m && d[u] + mv.length < d[v]) {
        d[v] = d[u] + mv.length;
        queue.push({d[v], v});
      }
    }
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace lattice
}  // namespace amha
