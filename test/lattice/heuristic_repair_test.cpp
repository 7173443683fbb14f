// Heuristic grids repaired after map changes (HeuristicGridBuilder::repair) must equal the grids
// computed from scratch on the new map, in every cell, whatever the change did: blocked or
// opened passages, cost changes, the goal itself blocked and freed again. Checked along chains
// of random updates, repairing grids that are one update old and grids several updates old
// (the changes of all the updates since then passed together).
#include <gtest/gtest.h>
#include <limits>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "amha_planner/lattice/detail/heuristic_grids.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "test_support.h"

namespace amha {
namespace lattice {
namespace {

std::string firstDifference(const std::vector<std::uint32_t>& a,
                            const std::vector<std::uint32_t>& b, int padded_width) {
  if (a.size() != b.size())
    return "sizes " + std::to_string(a.size()) + " and " + std::to_string(b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] != b[i]) {
      return "padded cell (" + std::to_string(i % padded_width) + ", " +
             std::to_string(i / padded_width) + "): " + std::to_string(a[i]) + " vs " +
             std::to_string(b[i]);
    }
  }
  return "";
}

void expectSame(const GoalHeuristics& repaired, const GoalHeuristics& full, int width,
                const std::string& what) {
  for (int k = 0; k < kNumGridKinds; ++k) {
    ASSERT_EQ(repaired.grids[k] == nullptr, full.grids[k] == nullptr) << what << ": grid " << k;
    if (full.grids[k]) {
      EXPECT_EQ(
          firstDifference(repaired.grids[k]->distances(), full.grids[k]->distances(), width + 4),
          "")
          << what << ": grid " << k;
    }
    EXPECT_EQ(repaired.scale[k], full.scale[k]) << what << ": grid " << k;
  }
  EXPECT_EQ(repaired.coarse, full.coarse) << what << ": coarse distances";
}

struct Robot {
  const char* name;
  LatticeConfig config;
  // Pass repair() the updated rectangle itself rather than the graph's recomputed area (which
  // has a margin): right for kinds whose cell levels depend on the cell alone (no openings).
  bool exact_changes = false;
};

std::vector<Robot> robots() {
  std::vector<Robot> out;
  LatticeConfig round;
  round.robot.radius = 0.2;
  out.push_back({"round robot", round});
  LatticeConfig polygon;
  polygon.robot.footprint =
      test::rectangle(0.35, 0.15);  // openings differ: four grids of their own
  out.push_back({"rectangular robot", polygon});
  LatticeConfig point;
  point.robot.radius = 0.0;  // grids that alias each other
  out.push_back({"point robot", point});
  LatticeConfig plain;
  plain.robot.radius = 0.15;
  plain.heuristics.num_inadmissible = 1;
  out.push_back({"round robot, no openings, exact changes", plain, true});
  return out;
}

// A random rectangle (some sticking out of the map) set to one cost or to a random mix.
CellRect randomUpdate(std::mt19937& rng, const GridMap& map, GridMap& next, int step) {
  const std::uint8_t values[] = {0,           0,           0,           17, 120, kInscribedCost,
                                 kLethalCost, kLethalCost, kUnknownCost};
  std::uniform_int_distribution<int> side(1, 40), px(-10, map.width), py(-10, map.height);
  std::uniform_int_distribution<int> pick(0, sizeof values - 1);
  CellRect r;
  r.x0 = px(rng);
  r.y0 = py(rng);
  r.x1 = r.x0 + side(rng);
  r.y1 = r.y0 + side(rng);
  const bool one_value = step % 3 != 0;
  const std::uint8_t v = values[pick(rng)];
  for (int y = std::max(r.y0, 0); y < std::min(r.y1, map.height); ++y) {
    for (int x = std::max(r.x0, 0); x < std::min(r.x1, map.width); ++x) {
      next.cost[static_cast<std::size_t>(y) * map.width + x] = one_value ? v : values[pick(rng)];
    }
  }
  return r;
}

TEST(HeuristicRepair, RepairedGridsEqualFreshOnesAlongChainsOfUpdates) {
  for (const Robot& robot : robots()) {
    std::mt19937 rng(11);
    std::shared_ptr<GridMap> map = test::randomMap(140, 100, 0.05, 5, 14, 40);
    auto graph = std::make_unique<LatticeGraph>(map, robot.config);
    auto builder = std::make_unique<HeuristicGridBuilder>(*graph);
    // Goals anywhere (free or not): their grids, and the changes since they were computed.
    // One goal of any heading: its coarse distances have a source per heading.
    struct Held {
      int x, y, heading;
      std::shared_ptr<const GoalHeuristics> grids;
      std::vector<CellRect> changed;
    };
    std::vector<Held> held;
    for (const auto& g :
         {std::array<int, 3>{70, 50, 0}, {12, 88, kAnyHeading}, {130, 7, 3}, {40, 30, 0}}) {
      held.push_back({g[0], g[1], g[2], builder->compute(g[0], g[1], g[2], true, 1), {}});
    }
    int repaired_grids = 0, in_place = 0;
    for (int step = 0; step < 30; ++step) {
      auto next = std::make_shared<GridMap>(*map);
      CellRect r;
      if (step % 5 != 4) {
        r = randomUpdate(rng, *map, *next, step);
      } else {  // now and then right at a goal, so that it gets blocked, then freed
        const Held& h = held[static_cast<std::size_t>(step / 10) % held.size()];
        r = {h.x - 3, h.y - 3, h.x + 4, h.y + 4};
        const std::uint8_t v = (step / 5) % 2 == 0 ? kLethalCost : 0;
        for (int y = r.y0; y < r.y1; ++y) {
          for (int x = r.x0; x < r.x1; ++x) {
            if (x >= 0 && y >= 0 && x < map->width && y < map->height)
              next->cost[static_cast<std::size_t>(y) * map->width + x] = v;
          }
        }
      }
      auto updated = std::make_unique<LatticeGraph>(*graph, next, r);
      auto updated_builder = std::make_unique<HeuristicGridBuilder>(*builder, *updated);
      for (Held& h : held) {
        h.changed.push_back(robot.exact_changes ? r : updated->recomputed());
        // Some grids are kept for several updates (their changes accumulate), others renewed:
        // those are handed over (moved) and repaired in place.
        const bool renew = (step + h.x) % 3 == 0;
        const DistanceGrid* old_anchor = h.grids->grids[0].get();
        const auto repaired = renew
                                  ? updated_builder->repair(std::move(h.grids), h.changed, true, 1)
                                  : updated_builder->repair(h.grids, h.changed, true, 1);
        const auto full = updated_builder->compute(h.x, h.y, h.heading, true, 1);
        ASSERT_TRUE(repaired && full);
        const std::string what = std::string(robot.name) + ", update " + std::to_string(step) +
                                 ", goal (" + std::to_string(h.x) + ", " + std::to_string(h.y) +
                                 ", heading " + std::to_string(h.heading) + "), grids " +
                                 std::to_string(h.changed.size()) + " update(s) old";
        expectSame(*repaired, *full, map->width, what);
        if (HasFailure()) return;
        ++repaired_grids;
        in_place += repaired->grids[0].get() == old_anchor;
        EXPECT_TRUE(renew || repaired->grids[0].get() != old_anchor)
            << what << ": a shared grid was modified";
        if (renew) {
          h.grids = repaired;
          h.changed.clear();
        }
      }
      map = next;
      graph = std::move(updated);
      builder = std::move(updated_builder);
    }
    EXPECT_EQ(repaired_grids, 30 * 4);
    EXPECT_GT(in_place, 20) << "grids handed over are repaired in place";
  }
}

// Distances that saturate (a long corridor of costly cells under the largest cost penalty)
// defeat the equality test of the repair (such grids are computed in full): still equal.
TEST(HeuristicRepair, GridsWithSaturatedDistancesComeOutEqual) {
  auto map = std::make_shared<GridMap>();
  map->width = 4000;
  map->height = 6;
  map->resolution = 0.05;
  map->cost.assign(static_cast<std::size_t>(map->width) * map->height, 200);
  LatticeConfig config;
  config.robot.radius = 0.0;
  config.cost.penalty = 10000.0;
  config.heuristics.coarse_anchor = false;
  auto graph = std::make_unique<LatticeGraph>(map, config);
  const HeuristicGridBuilder builder(*graph);
  const auto old = builder.compute(3, 3, 0, true, 1);
  ASSERT_TRUE(old && old->grids[0]);
  ASSERT_EQ(old->grids[0]->max_distance, kUnreachable - 1) << "the test wants saturated distances";
  auto next = std::make_shared<GridMap>(*map);
  const CellRect r{10, 0, 12, 6};
  for (int y = r.y0; y < r.y1; ++y) {
    for (int x = r.x0; x < r.x1; ++x) next->cost[static_cast<std::size_t>(y) * map->width + x] = 0;
  }
  const LatticeGraph updated(*graph, next, r);
  const HeuristicGridBuilder updated_builder(builder, updated);
  const auto repaired = updated_builder.repair(old, {updated.recomputed()}, true, 1);
  const auto full = updated_builder.compute(3, 3, 0, true, 1);
  ASSERT_TRUE(repaired && full);
  expectSame(*repaired, *full, map->width, "saturated corridor");
}

TEST(HeuristicRepair, NoChangeGivesTheSameGridsAndAStopIsHonoured) {
  auto map = test::randomMap(90, 70, 0.05, 3, 10, 20);
  const LatticeGraph graph(map, LatticeConfig());
  const HeuristicGridBuilder builder(graph);
  const auto grids = builder.compute(45, 35, 0, true, 1);
  ASSERT_TRUE(grids);
  const auto same = builder.repair(grids, {}, true, 1);
  ASSERT_TRUE(same);
  expectSame(*same, *grids, map->width, "no change");
  std::atomic<bool> cancel{true};
  const StopCondition stop(&cancel, std::numeric_limits<double>::infinity());
  EXPECT_EQ(builder.repair(grids, {CellRect{0, 0, 90, 70}}, true, 1, false, &stop), nullptr);
}

}  // namespace
}  // namespace lattice
}  // namespace amha
