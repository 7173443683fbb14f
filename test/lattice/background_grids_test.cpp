// Grids handed out before they are complete (HeuristicGridBuilder::compute with a search start):
// every cell read through DistanceGrid::at() is the complete grid's value, however early it is
// read; compute() returns once the start cell is final; a builder destroyed first stops its
// background threads and leaves lower bounds, never a hang; a stopped call returns null. A grid
// told to stop past a path's cost (GoalHeuristics::stopBeyond) is exact below it, a lower bound
// beyond, and holds memory only where it went; a planner that plans once stops its grids.
#include <gtest/gtest.h>
#include <sys/mman.h>
#include <unistd.h>

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
#include "amha_planner/lattice/lattice_planner.h"
#include "test_support.h"

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define AMHA_OWN_MALLOC 1  // their calloc may write the pages
#else
#define AMHA_OWN_MALLOC 0
#endif

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

// A point robot with the anchor's grid alone: one grid, for the one helper thread.
LatticeConfig anchorGridOnly() {
  LatticeConfig c;
  c.robot.radius = 0.0;
  c.heuristics.coarse_anchor = false;
  c.heuristics.num_inadmissible = 0;
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
        EXPECT_EQ(early->grids[k]->distances(), full->grids[k]->distances());
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
        EXPECT_EQ(repaired->grids[k]->distances(), full->grids[k]->distances()) << k;
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
  LatticeGraph g(test::freeMap(3000, 3000, 0.05), anchorGridOnly());
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

// The fraction of an array's pages resident in memory (mincore).
double residentFraction(const void* data, std::size_t bytes) {
  const std::size_t page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  const auto begin = reinterpret_cast<std::uintptr_t>(data) / page * page;
  const auto end = (reinterpret_cast<std::uintptr_t>(data) + bytes + page - 1) / page * page;
  std::vector<unsigned char> in((end - begin) / page);
  if (mincore(reinterpret_cast<void*>(begin), end - begin, in.data()) != 0) return -1.0;
  return static_cast<double>(
             std::count_if(in.begin(), in.end(), [](unsigned char c) { return (c & 1) != 0; })) /
         static_cast<double>(in.size());
}

// A large open map with a wall, the search starting a few cells from the goal, a path
// of about that length known at once: the grid stops where its keys pass that cost. Every cell
// below it reads exactly, every other one as the lower bound frontier - e, the grid is not
// complete but abandoned (so a planner's cache computes it again), and its untouched cells are
// pages never written.
TEST(BoundedGrids, AGridStoppedPastAPathsCostIsExactBelowItAndALowerBoundBeyond) {
  auto map = test::freeMap(2000, 2000, 0.05);
  for (int y = 900; y < 1100; ++y) map->cost[static_cast<std::size_t>(y) * 2000 + 980] = 254;
  LatticeGraph g(map, anchorGridOnly());
  const std::pair<int, int> goal{1000, 1000}, start{960, 1000};  // behind the wall
  HeuristicGridBuilder b(g);
  const auto early = b.compute(goal.first, goal.second, 0, false, 2, false, nullptr, &start);
  ASSERT_TRUE(early && early->grids[0] && early->grids[0]->progress);
  const DistanceGrid& grid = *early->grids[0];
  const GridProgress& progress = *grid.progress;
  // A path 1.5 times the start's grid distance: keys up to that are needed, no more.
  const std::uint32_t at_start = grid.at(start.first, start.second);
  const std::uint64_t path_cost = at_start * 3 / (2 * kGridFraction);
  early->stopBeyond(path_cost);
  const std::uint32_t stop_key = progress.stop_key.load();
  EXPECT_EQ(stop_key, path_cost * kGridFraction);
  early->stopBeyond(path_cost * 2);
  EXPECT_EQ(progress.stop_key.load(), stop_key) << "a later, worse path does not raise it";
  // The whole grid takes a hundred milliseconds or more (4 M cells): it stops long before.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!progress.abandoned.load() && !progress.complete.load() &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ASSERT_TRUE(progress.abandoned.load()) << "stopped at its key, not completed";
  EXPECT_FALSE(grid.complete());
  EXPECT_TRUE(grid.abandoned());
  EXPECT_TRUE(early->anyAbandoned());
  EXPECT_GE(progress.frontier.load(), stop_key);
  HeuristicGridBuilder again(g);
  const DistanceGrid full = again.computeOne(GridKind::kAnchor, goal.first, goal.second);
  EXPECT_FALSE(full.abandoned());
  int exact = 0, bounded = 0;
  for (int y = 0; y < full.height; y += 3) {
    for (int x = 0; x < full.width; x += 3) {
      const std::size_t i = paddedIndex(grid.width, x, y);
      const std::uint32_t v = grid.at(x, y), d = full.at(x, y), e = progress.direction.atIndex(i);
      if (progress.isFinal(i)) {
        ASSERT_EQ(v, d) << x << "," << y;
        ++exact;
        continue;
      }
      // Not final: its key d + e was not below the stop key, and it reads as a lower bound.
      ASSERT_GE(static_cast<std::uint64_t>(d) + e, stop_key) << x << "," << y;
      const std::uint32_t f = progress.frontier.load();
      ASSERT_EQ(v, f > e ? f - e : 0u) << x << "," << y;
      ASSERT_LE(v, d) << x << "," << y;
      ++bounded;
    }
  }
  EXPECT_GT(exact, 100);
  EXPECT_GT(bounded, 10 * exact) << "the path's ellipse is a small part of the map";
  if (!AMHA_OWN_MALLOC) {
    const double resident =
        residentFraction(grid.stored.data(), grid.stored.size() * sizeof(std::uint32_t));
    EXPECT_GE(resident, 0.0);
    EXPECT_LT(resident, 0.2) << "cells never reached are pages never written";
    EXPECT_GT(residentFraction(full.stored.data(), full.stored.size() * sizeof(std::uint32_t)),
              0.9);
  }
}

// A planner whose grids nobody reuses (cache.complete_grids off, as `amha plan`) stops them once
// it has a path: the same plans as a planner that completes them, and the next query to that
// goal computes its grids again instead of reading the stopped ones.
TEST(BoundedGrids, APlannerThatPlansOnceStopsItsGridsAndComputesThemAgainForTheNextQuery) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "grids complete before a search";
  auto map = test::freeMap(3000, 3000, 0.05);  // 9 M cells: the grid takes a while
  const Pose2D goal{75.0, 75.0, 0.0}, near{73.0, 75.5, 0.0}, other{77.0, 73.5, 3.14159};
  auto source = [](const PlanResult& r) {
    return std::string(heuristicSourceName(r.heuristic_source));
  };
  PlannerConfig search;  // A-MHA*
  SearchLimits limits;
  limits.time_limit_s = 60.0;
  LatticeConfig complete;
  complete.robot.radius = 0.0;
  complete.heuristics.kinematic_radius = 0.0;
  // One grid, on the helper, and no block abstraction for this thread to compute meanwhile: the
  // grid is far from complete when the search has its path.
  complete.heuristics.num_inadmissible = 0;
  complete.heuristics.coarse_anchor = false;
  LatticeConfig once = complete;
  once.cache.complete_grids = false;
  LatticePlanner a(map, complete), b(map, once);
  for (int q = 0; q < 2; ++q) {
    const Pose2D& from = q == 0 ? near : other;
    const PlanResult ra = a.plan(from, goal, search, limits);
    const PlanResult rb = b.plan(from, goal, search, limits);
    ASSERT_EQ(ra.search.status, SearchStatus::kProvenOptimal) << ra.message;
    ASSERT_EQ(rb.search.status, SearchStatus::kProvenOptimal) << rb.message;
    EXPECT_EQ(ra.solutions.back().search.cost, rb.solutions.back().search.cost);
    // The first query computes; then the complete grids are reused, the stopped ones are not.
    EXPECT_EQ(source(rb), "computed");
    EXPECT_EQ(source(ra), q == 0 ? "computed" : "cached");
  }
}

}  // namespace
}  // namespace lattice
}  // namespace amha
