// Goal tolerance: the substitute goal against a brute-force choice, the reachability test
// against the lattice's own reachable states, and LatticePlanner::plan with a tolerance end to
// end (obstructed goals only, hollow obstacles, errors, cancel).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <queue>
#include <random>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include "amha_planner/lattice/detail/goal_tolerance.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "test_support.h"

namespace amha {
namespace lattice {
namespace {

// nearestReachableGoal's specification, by looking at every state of the map.
GoalChoice bruteForceChoice(const LatticeGraph& g, const Pose2D& goal, double tol, int sx, int sy) {
  const std::vector<char> in = test::floodFill(g.map(), sx, sy);
  GoalChoice best;
  best.outcome = GoalChoice::Outcome::kNoFreePose;
  std::tuple<double, double, std::int64_t> key{INFINITY, INFINITY, 0};
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      const Pose2D c = g.stateToPose(x, y, 0);
      const double d = std::hypot(c.x - goal.x, c.y - goal.y);
      if (d > tol) continue;
      for (int h = 0; h < g.numHeadings(); ++h) {
        if (!g.stateValid(x, y, h)) continue;
        if (!in[static_cast<std::size_t>(y) * g.width() + x]) {
          if (best.outcome == GoalChoice::Outcome::kNoFreePose)
            best.outcome = GoalChoice::Outcome::kNoneReachable;
          continue;
        }
        const double hd =
            std::abs(std::remainder(g.stateToPose(x, y, h).theta - goal.theta, 2.0 * M_PI));
        const std::tuple<double, double, std::int64_t> k{
            d, hd, static_cast<std::int64_t>(y) * g.width() + x};
        if (k < key) {
          key = k;
          best.outcome = GoalChoice::Outcome::kFound;
          best.x = x;
          best.y = y;
          best.heading = h;
          best.distance = d;
          best.heading_difference = hd;
        }
      }
    }
  }
  return best;
}

// A random map with lethal rectangles, scattered inscribed and unknown cells and costs.
std::shared_ptr<GridMap> clutteredMap(unsigned seed, int size) {
  auto m = test::randomMap(size, size, 0.05, seed, size / 4, 120);
  std::mt19937 rng(seed + 1000);
  std::uniform_int_distribution<std::size_t> cell(0, m->cost.size() - 1);
  for (int k = 0; k < size * 2; ++k)
    m->cost[cell(rng)] = (k % 3 == 0) ? kUnknownCost : kInscribedCost;
  // A closed room (a lethal ring 2 cells thick, free inside), so that some free poses near a
  // goal are out of a start's reach.
  const int a = size / 6, b = size / 2;
  for (int y = a; y < b; ++y) {
    for (int x = a; x < b; ++x) {
      const bool wall = x < a + 2 || x >= b - 2 || y < a + 2 || y >= b - 2;
      m->cost[static_cast<std::size_t>(y) * size + x] = wall ? kLethalCost : kFreeCost;
    }
  }
  m->origin_x = -0.7;
  m->origin_y = 0.3;
  m->origin_yaw = (seed % 3 == 0) ? 0.4 : 0.0;
  return m;
}

TEST(GoalToleranceTest, ReachabilityEqualsAFloodFillOverManyQuestions) {
  // One object asked about every cell in random order: what it keeps between questions (the
  // start's side, the cells refused) must never change an answer.
  for (unsigned seed = 1; seed <= 8; ++seed) {
    const auto map = clutteredMap(seed, 40);
    std::mt19937 rng(seed);
    int largest = 0;
    for (int start = 0; start < 6; ++start) {
      const int sx = static_cast<int>(rng() % 40), sy = static_cast<int>(rng() % 40);
      const std::vector<char> want = test::floodFill(*map, sx, sy);
      std::vector<int> cells(map->cost.size());
      for (std::size_t i = 0; i < cells.size(); ++i) cells[i] = static_cast<int>(i);
      std::shuffle(cells.begin(), cells.end(), rng);
      CentreReachability reach(*map, sx, sy);
      int yes = 0;
      for (const int c : cells) {
        const auto a = reach.reaches(c % 40, c / 40, nullptr);
        ASSERT_EQ(a == CentreReachability::Answer::kYes, want[c] != 0)
            << "seed " << seed << " cell " << c;
        yes += a == CentreReachability::Answer::kYes;
      }
      largest = std::max(largest, yes);
    }
    EXPECT_GT(largest, 100) << "seed " << seed;  // a real part of the map was asked about
  }
}

TEST(GoalToleranceTest, ChoiceEqualsBruteForce) {
  int found = 0, none_reachable = 0, no_free = 0;
  for (unsigned seed = 1; seed <= 12; ++seed) {
    LatticeConfig c;
    c.motion.turning_radius = 0.2;
    if (seed % 2 == 0) {
      c.robot.footprint = test::rectangle(0.12, 0.05);
    } else {
      c.robot.radius = 0.08;
    }
    LatticeGraph g(clutteredMap(seed, 48), c);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int q = 0; q < 40; ++q) {
      // A valid start and a goal anywhere in the map (usually free: then the goal's own cell
      // competes too), with tolerances from none to the whole map.
      int sx = 0, sy = 0;
      do {
        sx = static_cast<int>(u(rng) * g.width());
        sy = static_cast<int>(u(rng) * g.height());
      } while (!g.stateValid(sx, sy, 0));
      const Pose2D corner = g.cellPoseToMap(0, 0, Pose2D{-0.025, -0.025, 0.0});
      const double gx = u(rng) * g.width() * 0.05, gy = u(rng) * g.height() * 0.05;
      const double cy = std::cos(g.map().origin_yaw), sy_ = std::sin(g.map().origin_yaw);
      const Pose2D goal{corner.x + cy * gx - sy_ * gy, corner.y + sy_ * gx + cy * gy,
                        (u(rng) - 0.5) * 7.0};
      const double tol = q % 10 == 9 ? INFINITY : u(rng) * u(rng) * 1.5;
      const GoalChoice got = nearestReachableGoal(g, goal, tol, sx, sy, nullptr);
      const GoalChoice want = bruteForceChoice(g, goal, tol, sx, sy);
      ASSERT_EQ(static_cast<int>(got.outcome), static_cast<int>(want.outcome))
          << "seed " << seed << " query " << q;
      if (want.outcome == GoalChoice::Outcome::kFound) {
        EXPECT_EQ(got.x, want.x);
        EXPECT_EQ(got.y, want.y);
        EXPECT_EQ(got.heading, want.heading);
        EXPECT_EQ(got.distance, want.distance);
        EXPECT_LE(got.distance, tol);
        ++found;
      }
      none_reachable += want.outcome == GoalChoice::Outcome::kNoneReachable;
      no_free += want.outcome == GoalChoice::Outcome::kNoFreePose;
    }
  }
  // Every outcome was exercised.
  EXPECT_GT(found, 100);
  EXPECT_GT(none_reachable, 0);
  EXPECT_GT(no_free, 10);
}

TEST(GoalToleranceTest, EveryStateTheLatticeReachesIsInTheComponent) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    LatticeConfig c;
    c.motion.turning_radius = 0.2;
    c.motion.allow_reverse = seed % 2 == 0;
    c.robot.footprint = test::rectangle(0.1, 0.04);
    LatticeGraph g(clutteredMap(seed, 40), c);
    std::mt19937 rng(seed);
    std::size_t largest = 0;
    for (int start = 0; start < 8; ++start) {
      int sx = 0, sy = 0, sh = 0;
      do {
        sx = static_cast<int>(rng() % g.width());
        sy = static_cast<int>(rng() % g.height());
        sh = static_cast<int>(rng() % g.numHeadings());
      } while (!g.stateValid(sx, sy, sh));
      // Breadth-first over the lattice's own edges.
      std::set<std::tuple<int, int, int>> seen{{sx, sy, sh}};
      std::queue<std::tuple<int, int, int>> q;
      q.push({sx, sy, sh});
      CentreReachability reach(g.map(), sx, sy);
      while (!q.empty()) {
        const auto [x, y, h] = q.front();
        q.pop();
        ASSERT_EQ(reach.reaches(x, y, nullptr), CentreReachability::Answer::kYes) << x << ", " << y;
        for (const LatticeAction* a = g.actionsBegin(h); a != g.actionsEnd(h); ++a) {
          if (g.edgeCost(x, y, *a) == kInvalidEdge) continue;
          const std::tuple<int, int, int> n{x + a->dx, y + a->dy, a->end_heading};
          if (seen.insert(n).second) q.push(n);
        }
      }
      largest = std::max(largest, seen.size());
    }
    EXPECT_GT(largest, 1000u) << "seed " << seed;  // the check covered a real part of the map
  }
}

// 80 x 80 cells of 5 cm, free but for a hollow square box: walls 2 cells thick around
// x, y in [30, 50), so its inside (x, y in [32, 48)) is free and closed.
std::shared_ptr<GridMap> hollowBoxMap() {
  auto m = std::make_shared<GridMap>();
  m->width = m->height = 80;
  m->resolution = 0.05;
  m->cost.assign(80 * 80, kFreeCost);
  for (int y = 30; y < 50; ++y) {
    for (int x = 30; x < 50; ++x) {
      if (x < 32 || x >= 48 || y < 32 || y >= 48) m->cost[y * 80 + x] = kLethalCost;
    }
  }
  return m;
}

GoalOptions tolerance(double metres) {
  GoalOptions o;
  o.tolerance = metres;
  return o;
}

Pose2D cellCentre(int x, int y, double theta = 0.0) {
  return {(x + 0.5) * 0.05, (y + 0.5) * 0.05, theta};
}

LatticeConfig boxRobot() {
  LatticeConfig c;
  c.robot.radius = 0.1;  // 2 cells
  c.motion.turning_radius = 0.2;
  return c;
}

TEST(GoalToleranceTest, PlanSubstitutesObstructedGoalsOnly) {
  LatticePlanner planner(hollowBoxMap(), boxRobot());
  const PlannerConfig astar = defaultConfig(Algorithm::kAStar);
  const Pose2D start = cellCentre(10, 10);

  // A free goal is planned to exactly, whatever the tolerance.
  const Pose2D free_goal = cellCentre(65, 12, 1.0);
  const PlanResult exact = planner.plan(start, free_goal, astar, SearchLimits());
  const PlanResult tolerant = planner.plan(start, free_goal, tolerance(0.5), astar, SearchLimits());
  ASSERT_TRUE(exact.hasSolution());
  ASSERT_TRUE(tolerant.hasSolution());
  EXPECT_FALSE(tolerant.goal_substituted);
  ASSERT_TRUE(tolerant.planned_goal.has_value());
  EXPECT_EQ(tolerant.best().search.cost, exact.best().search.cost);
  EXPECT_NEAR(tolerant.planned_goal->x, free_goal.x, 1e-9);
  EXPECT_NEAR(tolerant.planned_goal->y, free_goal.y, 1e-9);

  // A goal on the box's outer wall: refused without a tolerance, replaced with one by the
  // nearest free cell outside (x = 27: the robot's 2-cell radius keeps it off x = 28, 29).
  const Pose2D on_wall = cellCentre(30, 40, 0.0);
  PlanResult r = planner.plan(start, on_wall, astar, SearchLimits());
  EXPECT_EQ(r.error, QueryError::kGoalInCollision);
  r = planner.plan(start, on_wall, tolerance(0.5), astar, SearchLimits());
  ASSERT_EQ(r.error, QueryError::kNone) << r.message;
  ASSERT_TRUE(r.hasSolution());
  EXPECT_TRUE(r.goal_substituted);
  EXPECT_NE(r.message.find("nearest reachable collision-free pose"), std::string::npos)
      << r.message;
  ASSERT_TRUE(r.planned_goal.has_value());
  EXPECT_NEAR(r.planned_goal->x, cellCentre(27, 40).x, 1e-9);
  EXPECT_NEAR(r.planned_goal->y, cellCentre(27, 40).y, 1e-9);
  EXPECT_NEAR(r.planned_goal->theta, 0.0, 1e-9);
  const Pose2D& end = r.solutions.back().poses.back();
  EXPECT_NEAR(end.x, r.planned_goal->x, 1e-9);
  EXPECT_NEAR(end.y, r.planned_goal->y, 1e-9);
  EXPECT_LE(std::hypot(end.x - on_wall.x, end.y - on_wall.y), 0.5);

  // A goal on the inner side of the wall: the free inside (x = 34, 3 cells away) is nearer
  // than the outside (x = 27, 4 away), but closed to a start outside, so the substitute is
  // outside; from a start inside, it is inside.
  const Pose2D inner_wall = cellCentre(31, 40, 0.0);
  r = planner.plan(start, inner_wall, tolerance(0.5), astar, SearchLimits());
  ASSERT_TRUE(r.hasSolution()) << r.message;
  EXPECT_LT(r.planned_goal->x, 30 * 0.05);
  r = planner.plan(cellCentre(40, 40), inner_wall, tolerance(0.5), astar, SearchLimits());
  ASSERT_TRUE(r.hasSolution()) << r.message;
  EXPECT_NEAR(r.planned_goal->x, cellCentre(34, 40).x, 1e-9);

  // Too small a tolerance: still in collision, and the message says why.
  r = planner.plan(start, on_wall, tolerance(0.1), astar, SearchLimits());
  EXPECT_EQ(r.error, QueryError::kGoalInCollision);
  EXPECT_NE(r.message.find("goal tolerance"), std::string::npos) << r.message;
  EXPECT_FALSE(r.goal_substituted);
  EXPECT_TRUE(r.solutions.empty());

  // From inside the box, free poses near an outside goal exist but are all out of reach.
  r = planner.plan(cellCentre(40, 40), cellCentre(29, 10, 0.0), tolerance(0.3), astar,
                   SearchLimits());
  EXPECT_EQ(r.error, QueryError::kNone);  // (29, 10) is free: planned to exactly, and unreachable
  EXPECT_EQ(r.search.status, SearchStatus::kNoSolution);
  // (29, 40) is free, but the robot there touches the wall; within 0.12 m only x = 27, outside.
  r = planner.plan(cellCentre(40, 40), cellCentre(29, 40, 0.0), tolerance(0.12), astar,
                   SearchLimits());
  EXPECT_EQ(r.error, QueryError::kGoalUnreachable) << r.message;
  EXPECT_STREQ(queryErrorName(r.error), "goal_unreachable");

  // Out of the map stays an error; bad tolerances are refused.
  EXPECT_EQ(planner.plan(start, {-0.2, 1.0, 0.0}, tolerance(1.0), astar, SearchLimits()).error,
            QueryError::kGoalOutOfMap);
  for (const double bad : {-0.1, static_cast<double>(NAN), static_cast<double>(INFINITY)}) {
    EXPECT_THROW(planner.plan(start, on_wall, tolerance(bad), astar, SearchLimits()),
                 std::invalid_argument);
  }
}

TEST(GoalToleranceTest, SubstitutePathsValidateAndAreOptimalForTheSubstitute) {
  // A substitute is an ordinary goal: A* costs what it costs to that goal asked for exactly,
  // and every algorithm's solutions end there within their certified bounds of that optimum.
  LatticePlanner planner(hollowBoxMap(), boxRobot());
  const Pose2D start = cellCentre(10, 70, 0.0), goal = cellCentre(49, 35, 2.0);
  const PlanResult a =
      planner.plan(start, goal, tolerance(0.4), defaultConfig(Algorithm::kAStar), SearchLimits());
  ASSERT_TRUE(a.hasSolution()) << a.message;
  ASSERT_TRUE(a.goal_substituted);
  const PlanResult direct =
      planner.plan(start, *a.planned_goal, defaultConfig(Algorithm::kAStar), SearchLimits());
  ASSERT_TRUE(direct.hasSolution());
  EXPECT_EQ(a.best().search.cost, direct.best().search.cost);
  for (const Algorithm alg :
       {Algorithm::kAmhaStar, Algorithm::kMhaStar, Algorithm::kAraStar, Algorithm::kAnaStar}) {
    const PlanResult r =
        planner.plan(start, goal, tolerance(0.4), defaultConfig(alg), SearchLimits());
    ASSERT_TRUE(r.hasSolution()) << algorithmName(alg);
    EXPECT_TRUE(r.goal_substituted);
    for (const LatticeSolution& s : r.solutions) {
      EXPECT_NEAR(s.poses.back().x, a.planned_goal->x, 1e-9) << algorithmName(alg);
      EXPECT_NEAR(s.poses.back().y, a.planned_goal->y, 1e-9) << algorithmName(alg);
      EXPECT_LE(
          static_cast<double>(s.search.cost),
          s.search.certified_bound * static_cast<double>(direct.best().search.cost) * (1 + 1e-12))
          << algorithmName(alg);
    }
  }
}

TEST(GoalToleranceTest, CancelBeforeTheChoiceStopsIt) {
  LatticePlanner planner(hollowBoxMap(), boxRobot());
  std::atomic<bool> cancel{true};
  SearchLimits limits;
  limits.cancel = &cancel;
  const PlanResult r = planner.plan(cellCentre(10, 10), cellCentre(30, 40), tolerance(0.5),
                                    defaultConfig(Algorithm::kAStar), limits);
  EXPECT_EQ(r.error, QueryError::kNone);
  EXPECT_EQ(r.search.status, SearchStatus::kCancelled);
  EXPECT_TRUE(r.solutions.empty());
  EXPECT_FALSE(r.goal_substituted);
  EXPECT_FALSE(r.planned_goal.has_value());
}

}  // namespace
}  // namespace lattice
}  // namespace amha
