// Grids handed out before they are complete (HeuristicGridBuilder::compute with a search start):
// every cell read through DistanceGrid::at() is the complete grid's value, however early it is
// read; compute() returns once the start cell is final; a builder destroyed first stops its
// background threads and leaves lower bounds, never a hang; a stopped call returns null.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <numeric>
#include <thread>
#include <utility>
#include <vector>

#include "amha_planner/lattice/detail/heuristic_grids.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "test_support.h"

namespace amha {
namespace lattice {
namespace {

// A round robot with openings of its own, so that the anchor and the opening grids differ.
LatticeConfig roundRobot() {
  LatticeConfig c;
  c.motion.turning_radius = 0.2;
  c.robot.radius = 0.08;
  c.cost.penalty = 3.0;
  c.heuristics.kinematic_radius = 0.0;
  return c;
}

// The padded cells of a grid, farthest from the goal first: read first, they are the likeliest
// to be unsettled when compute() returns.
std::vector<std::pair<int, int>> farthestFirst(const DistanceGrid& full) {
  std::vector<std::pair<int, int>> cells;
  for (int y = 0; y < full.height; ++y) {
    for (int x = 0; x < full.width; ++x) cells.emplace_back(x, y);
  }
  std::stable_sort(cells.begin(), cells.end(), [&](const auto& a, const auto& b) {
    return full.at(a.first, a.second) > full.at(b.first, b.second);
  });
  return cells;
}

// With one grid for the one helper it is an A* toward the start; with more grids than helpers
// (the anchor's and the openings'), Dijkstras (the calling thread completes the rest first).
void everyCellReadsAsTheCompleteGrid(const LatticeConfig& config, bool toward_start) {
  for (unsigned seed : {1u, 2u, 3u}) {
    auto map = test::randomMap(300, 220, 0.05, seed, 60, seed == 3 ? 0 : 120);
    const std::pair<int, int> goal{40, 30}, start{260, 190};
    map->cost[goal.second * map->width + goal.first] = 0;
    map->cost[start.second * map->width + start.first] = 0;
    LatticeGraph g(map, config);
    HeuristicGridBuilder b(g);
    const auto full = b.compute(goal.first, goal.second, 0, true, 2);
    const auto early = b.compute(goal.first, goal.second, 0, true, 2, false, nullptr, &start);
    ASSERT_TRUE(full && early);
    int handed_early = 0;
    for (int k = 0; k < kNumGridKinds; ++k) {
      ASSERT_EQ(full->grids[k] == nullptr, early->grids[k] == nullptr) << k;
      if (!full->grids[k]) continue;
      const DistanceGrid& e = *early->grids[k];
      EXPECT_EQ(full->grids[k]->progress, nullptr) << "no search start: complete on return";
      if (e.progress) {
        ++handed_early;
        const std::size_t i = paddedIndex(e.width, start.first, start.second);
        EXPECT_TRUE(e.progress->isFinal(i) || e.progress->complete.load())
            << "seed " << seed << " grid " << k;
        EXPECT_EQ(e.progress->direction.per_cell > 0.0, toward_start) << "seed " << seed;
      }
    }
    EXPECT_GT(handed_early, 0) << "two threads and a search start: the grids go to a helper";
    for (int k = 0; k < kNumGridKinds; ++k) {
      if (!full->grids[k]) continue;
      for (const auto& [x, y] : farthestFirst(*full->grids[k])) {
        ASSERT_EQ(early->grids[k]->at(x, y), full->grids[k]->at(x, y))
            << "seed " << seed << " grid " << k << " cell " << x << "," << y;
      }
      if (early->grids[k]->progress) {
        ASSERT_TRUE(early->grids[k]->progress->waitComplete());
        EXPECT_EQ(early->grids[k]->dist, full->grids[k]->dist);
        EXPECT_EQ(early->grids[k]->max_distance, full->grids[k]->max_distance);
      }
      EXPECT_EQ(early->scale[k], full->scale[k]);
    }
    EXPECT_EQ(early->coarse, full->coarse);
    // Repairing grids handed out early waits for them: the same grids again (nothing changed).
    const auto repaired = b.repair(early, {}, true, 2);
    ASSERT_TRUE(repaired);
    for (int k = 0; k < kNumGridKinds; ++k) {
      if (full->grids[k]) {
        EXPECT_EQ(repaired->grids[k]->dist, full->grids[k]->dist) << k;
      }
    }
  }
}

TEST(BackgroundThreadGrids, EveryCellReadsAsTheCompleteGrid) {
  everyCellReadsAsTheCompleteGrid(roundRobot(), false);
  LatticeConfig one_grid = roundRobot();
  one_grid.heuristics.num_inadmissible = 0;
  everyCellReadsAsTheCompleteGrid(one_grid, true);
}

// A large open map, the search starting next to the goal: compute() returns long before the
// grid is complete; destroying the builder then stops the background thread, and what was not
// settled reads as a lower bound instead of waiting forever.
TEST(BackgroundThreadGrids, ReturnsOnceTheStartIsFinalAndStopsWithTheBuilder) {
  auto map = std::make_shared<GridMap>();
  map->width = map->height = 3000;
  map->resolution = 0.05;
  map->cost.assign(static_cast<std::size_t>(map->width) * map->height, 0);
  LatticeConfig c;
  c.robot.radius = 0.0;
  c.heuristics.coarse_anchor = false;
  c.heuristics.num_inadmissible = 0;
  c.heuristics.kinematic_radius = 0.0;
  LatticeGraph g(map, c);
  const std::pair<int, int> goal{1500, 1500}, start{1501, 1500};
  auto b = std::make_unique<HeuristicGridBuilder>(g);
  const auto early = b->compute(goal.first, goal.second, 0, false, 2, false, nullptr, &start);
  ASSERT_TRUE(early && early->grids[0] && early->grids[0]->progress);
  const DistanceGrid& grid = *early->grids[0];
  const GridProgress& progress = *grid.progress;
  // The whole grid takes hundreds of milliseconds (9 M cells); the start is one step away.
  EXPECT_FALSE(progress.complete.load()) << "returned only when complete";
  EXPECT_GT(grid.at(start.first, start.second), 0u);
  EXPECT_LT(grid.at(start.first, start.second), kUnreachable);
  b.reset();
  EXPECT_TRUE(progress.abandoned.load() || progress.complete.load());
  // Every cell reads as its distance or, abandoned before it was final, as a lower bound of it:
  // the last key popped less the cell's e (GridProgress::read).
  HeuristicGridBuilder again(g);
  const DistanceGrid full = again.computeOne(GridKind::kAnchor, goal.first, goal.second);
  int bounded = 0;
  for (int y = 0; y < full.height; y += 7) {
    for (int x = 0; x < full.width; x += 7) {
      const std::size_t i = paddedIndex(grid.width, x, y);
      const std::uint32_t v = grid.at(x, y);
      if (progress.complete.load() || progress.isFinal(i)) {
        ASSERT_EQ(v, full.at(x, y)) << x << "," << y;
        continue;
      }
      const std::uint32_t f = progress.frontier.load(), e = progress.direction.atIndex(i);
      ASSERT_EQ(v, f > e ? f - e : 0u) << x << "," << y;
      ASSERT_LE(v, full.at(x, y)) << x << "," << y;
      ++bounded;
    }
  }
  EXPECT_GT(bounded, 0) << "abandoned long before the far cells";
}

TEST(BackgroundThreadGrids, AStoppedCallReturnsNull) {
  auto map = test::randomMap(300, 220, 0.05, 4, 60, 120);
  LatticeGraph g(map, roundRobot());
  HeuristicGridBuilder b(g);
  std::atomic<bool> cancel{true};
  const StopCondition stop(&cancel, 10.0);
  const std::pair<int, int> start{200, 100};
  EXPECT_EQ(b.compute(40, 30, 0, true, 2, false, &stop, &start), nullptr);
  cancel = false;
  const StopCondition go(&cancel, 10.0);
  EXPECT_NE(b.compute(40, 30, 0, true, 2, false, &go, &start), nullptr)
      << "the builder still works";
}

// A helper that completes its grids lets go of them: once the caller drops the heuristics, the
// grids are freed without another compute() or the builder's end (a server between queries).
TEST(BackgroundThreadGrids, ACompletedHelperReleasesItsGrids) {
  auto map = test::randomMap(300, 220, 0.05, 5, 60, 120);
  const std::pair<int, int> goal{40, 30}, start{41, 30};
  map->cost[goal.second * map->width + goal.first] = 0;
  map->cost[start.second * map->width + start.first] = 0;
  LatticeGraph g(map, roundRobot());
  HeuristicGridBuilder b(g);
  auto early = b.compute(goal.first, goal.second, 0, true, 2, false, nullptr, &start);
  ASSERT_TRUE(early && early->grids[0] && early->grids[0]->progress);
  const std::shared_ptr<const GridProgress> progress = early->grids[0]->progress;
  const std::weak_ptr<const DistanceGrid> grid = early->grids[0];
  ASSERT_TRUE(progress->waitComplete());
  early.reset();
  // The helper may still be between publishing completion and ending; a few seconds at most.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!grid.expired() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_TRUE(grid.expired()) << "the finished job still holds the grid";
}

}  // namespace
}  // namespace lattice
}  // namespace amha
