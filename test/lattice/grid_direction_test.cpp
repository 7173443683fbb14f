// GridDirection, the A* order of the grids handed out early: its walk is the empty grid's
// shortest walk of the grid's moves, its e is consistent for every move at the builder's scale
// (so a cell's distance is final when popped), and a scale one unit too large is caught.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <queue>
#include <utility>
#include <vector>

#include "amha_planner/lattice/detail/grid_moves.h"
#include "amha_planner/lattice/detail/heuristic_grids.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "test_support.h"

namespace amha {
namespace lattice {
namespace {

constexpr int kSide = 41;  // an empty square, the direction's cell at its centre

// Shortest walks of `moves` from the centre of an empty kSide x kSide square (Dijkstra).
std::vector<double> emptyWalks(const std::vector<GridMove>& moves) {
  std::vector<double> walk(kSide * kSide, INFINITY);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  const int centre = (kSide / 2) * kSide + kSide / 2;
  walk[centre] = 0.0;
  open.push({0.0, centre});
  while (!open.empty()) {
    const auto [d, i] = open.top();
    open.pop();
    if (d > walk[i]) continue;
    for (const GridMove& m : moves) {
      const int x = i % kSide + m.dx, y = i / kSide + m.dy;
      if (x < 0 || y < 0 || x >= kSide || y >= kSide) continue;
      const int j = y * kSide + x;
      if (d + m.length < walk[j] - 1e-12) {
        walk[j] = d + m.length;
        open.push({walk[j], j});
      }
    }
  }
  return walk;
}

GridDirection centred(double per_cell, bool knights) {
  GridDirection d;
  d.x = d.y = kSide / 2;
  d.padded_width = kSide;
  d.per_cell = per_cell;
  d.knights = knights;
  return d;
}

TEST(GridDirection, IsTheEmptyGridsShortestWalk) {
  for (int connectivity : {8, 16}) {
    const std::vector<double> walk = emptyWalks(gridMoves(connectivity));
    const GridDirection d = centred(1000.0, connectivity == 16);
    for (int y = 0; y < kSide; ++y) {
      for (int x = 0; x < kSide; ++x) {
        // Within the rounding of the two sums (the walk's floor may differ by one).
        const double expected = 1000.0 * walk[y * kSide + x];
        EXPECT_NEAR(d.at(x, y), std::floor(expected), 1.0)
            << connectivity << "-connected, cell " << x << "," << y;
        EXPECT_EQ(d.at(x, y), d.atIndex(static_cast<std::size_t>(y) * kSide + x));
      }
    }
  }
}

// The number of (cell, move) pairs of the square where e drops by more than the move's step.
int inconsistentMoves(const GridDirection& d, const std::vector<GridMove>& moves,
                      const std::vector<std::uint32_t>& steps) {
  int bad = 0;
  for (int y = 2; y < kSide - 2; ++y) {
    for (int x = 2; x < kSide - 2; ++x) {
      for (std::size_t m = 0; m < moves.size(); ++m) {
        const std::uint32_t a = d.at(x, y), b = d.at(x + moves[m].dx, y + moves[m].dy);
        if (a > b + steps[m]) ++bad;
      }
    }
  }
  return bad;
}

// The direction an early compute() chose, checked on every move of the square with the steps
// the builder uses for free cells (floor(units per cell x length x kGridFraction)), on maps
// whose units give scales of a few to hundreds per cell.
TEST(GridDirection, IsConsistentAtTheBuildersScale) {
  for (double resolution : {0.05, 0.0031, 0.5}) {
    // Large enough for compute() to use a helper thread (it computes small maps at once).
    auto map = test::randomMap(200, 150, resolution, 3, 60, 0);
    const std::pair<int, int> goal{10, 10}, start{180, 130};
    map->cost[goal.second * map->width + goal.first] = 0;
    map->cost[start.second * map->width + start.first] = 0;
    LatticeConfig c;
    c.motion.turning_radius = resolution * 4;
    c.robot.radius = 0.0;
    c.heuristics.kinematic_radius = 0.0;
    c.heuristics.coarse_anchor = false;
    c.heuristics.num_inadmissible = 0;
    LatticeGraph g(map, c);
    HeuristicGridBuilder b(g);
    const auto early = b.compute(goal.first, goal.second, 0, false, 2, false, nullptr, &start);
    ASSERT_TRUE(early && early->grids[0]);
    ASSERT_TRUE(early->grids[0]->progress) << "handed out early, with a direction";
    GridDirection d = early->grids[0]->progress->direction;
    ASSERT_GT(d.per_cell, 0.0) << resolution;
    EXPECT_EQ(d.knights, c.heuristics.anchor_connectivity == 16);
    const std::vector<GridMove> moves = gridMoves(c.heuristics.anchor_connectivity);
    std::vector<std::uint32_t> steps;
    for (std::size_t m = 0; m < moves.size(); ++m) {
      steps.push_back(static_cast<std::uint32_t>(
          std::floor(g.gridAnchorMoveUnits()[m] * moves[m].length * kGridFraction)));
    }
    // Centred in the square (the padded coordinates do not matter to the differences).
    d.x = d.y = kSide / 2;
    d.padded_width = kSide;
    EXPECT_EQ(inconsistentMoves(d, moves, steps), 0) << "resolution " << resolution;
    // The mutation: one unit more per cell and some move's step is exceeded.
    GridDirection raised = d;
    raised.per_cell = d.per_cell + 1.0;
    EXPECT_GT(inconsistentMoves(raised, moves, steps), 0) << "resolution " << resolution;
    EXPECT_TRUE(early->grids[0]->progress->waitComplete());
  }
}

}  // namespace
}  // namespace lattice
}  // namespace amha
