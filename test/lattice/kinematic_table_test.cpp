// The kinematic table (kinematic_table.h): every entry equals min(T, floor(G)) with T from an
// unconfined Dijkstra on the empty lattice, for every heading (through the symmetries),
// direction and the any-heading goal; the anchor that takes it stays consistent on every edge
// of real and generated maps, the edges across the disc's edge included, and admissible
// against the exact cost-to-go; the naive construction (T inside, Euclidean outside) is shown
// to break there; a table raised by one unit is caught; tables are shared and cancellable.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <queue>
#include <random>
#include <tuple>

#include <gtest/gtest.h>

#include "amha_planner/lattice/detail/heuristic_grids.h"
#include "amha_planner/lattice/detail/kinematic_table.h"
#include "amha_planner/lattice/detail/lattice_problem.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/lattice/map_loaders.h"
#include "test_support.h"

namespace amha {
namespace lattice {

// Reaches into a slice to mutate it (the mutation test).
struct KinematicTableTestAccess {
  // Raises the entry that (dx, dy, h) reads (in a folded slice, maybe its mirror image's).
  static void raise(KinematicSlice& s, int dx, int dy, int h) {
    if (!s.kept(dx, dy)) s.fold(&dx, &dy, &h);
    ++s.values_[s.index(dx, dy, h)];
  }
  static KinematicLookup with(KinematicLookup lookup, std::shared_ptr<const KinematicSlice> slice) {
    lookup.slice_ = std::move(slice);
    return lookup;
  }
};

namespace {

using Direction = KinematicTables::Direction;

std::vector<KinematicMove> movesOf(const LatticeGraph& g) {
  std::vector<KinematicMove> m;
  for (const LatticeAction& a : g.actions())
    m.push_back({a.dx, a.dy, a.start_heading, a.end_heading, a.base_cost});
  return m;
}

// Exact cost-to-go (kToGoal) or cost-from (kFromStart) on the empty lattice, by a Dijkstra over
// a box of half-width `half` around the origin: exact for every state whose cheapest path stays
// in the box, which holds for costs up to s * half (every move costs at least s per cell).
struct EmptyLatticeCosts {
  int half, nh;
  std::vector<Cost> d;
  Cost at(int x, int y, int h) const {
    return d[(static_cast<std::size_t>(y + half) * (2 * half + 1) + (x + half)) * nh + h];
  }
};

EmptyLatticeCosts emptyLatticeCosts(const std::vector<KinematicMove>& moves, int nh, int half,
                                    Direction dir, int heading) {
  EmptyLatticeCosts out{half, nh, {}};
  const int side = 2 * half + 1;
  out.d.assign(static_cast<std::size_t>(side) * side * nh, kInfiniteCost);
  auto index = [&](int x, int y, int h) {
    return (static_cast<std::size_t>(y + half) * side + (x + half)) * nh + h;
  };
  using Item = std::pair<Cost, std::tuple<int, int, int>>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  for (int h = 0; h < nh; ++h) {
    if (heading != kAnyHeading && h != heading) continue;
    out.d[index(0, 0, h)] = 0;
    q.push({0, {0, 0, h}});
  }
  while (!q.empty()) {
    const auto [c, st] = q.top();
    q.pop();
    const auto [x, y, h] = st;
    if (c != out.d[index(x, y, h)]) continue;
    for (const KinematicMove& m : moves) {
      const bool to_goal = dir == Direction::kToGoal;
      if ((to_goal ? m.end_heading : m.start_heading) != h) continue;
      const int px = to_goal ? x - m.dx : x + m.dx, py = to_goal ? y - m.dy : y + m.dy;
      const int ph = to_goal ? m.start_heading : m.end_heading;
      if (std::abs(px) > half || std::abs(py) > half) continue;
      const std::size_t j = index(px, py, ph);
      if (c + m.cost < out.d[j]) {
        out.d[j] = c + m.cost;
        q.push({out.d[j], {px, py, ph}});
      }
    }
  }
  return out;
}

// Entries of `lookup` that differ from min(T, floor(G)); T from `exact` (a box of half-width
// >= 2R, so exact wherever T <= G).
int mismatches(const KinematicLookup& lookup, const EmptyLatticeCosts& exact,
               const KinematicTables& t, std::string* first) {
  const int R = t.radius();
  int bad = 0;
  for (int y = -R; y <= R; ++y) {
    for (int x = -R; x <= R; ++x) {
      if (x * x + y * y > R * R) continue;
      const double g = std::floor(t.costPerCell() * (2.0 * R - std::hypot(x, y)));
      for (int h = 0; h < t.numHeadings(); ++h) {
        const double want = std::min(static_cast<double>(exact.at(x, y, h)), g);
        const double got = lookup.value(x, y, h);
        if (got != want) {
          if (bad++ == 0 && first != nullptr) {
            *first = "(" + std::to_string(x) + ", " + std::to_string(y) + ", " + std::to_string(h) +
                     "): " + std::to_string(got) + " instead of " + std::to_string(want);
          }
        }
      }
    }
  }
  return bad;
}

struct NamedConfig {
  const char* name;
  LatticeConfig config;
  double resolution;
};

std::vector<NamedConfig> primitiveSets() {
  std::vector<NamedConfig> sets;
  LatticeConfig c;
  c.motion.turning_radius = 0.2;
  sets.push_back({"generated, turns in place", c, 0.05});
  c.motion.turn_in_place = false;
  sets.push_back({"generated, no turns in place", c, 0.05});
  c.motion.allow_reverse = true;
  sets.push_back({"generated, reverse", c, 0.05});
  c = LatticeConfig();
  c.motion.num_headings = 8;
  c.motion.turning_radius = 0.15;
  sets.push_back({"generated, 8 headings", c, 0.05});
  const std::string data = test::sharedData();
  if (!data.empty()) {
    c = LatticeConfig();
    c.motion.mprim_file = data + "/sbpl/pr2.mprim";
    sets.push_back({"SBPL pr2.mprim (uniform headings)", c, 0.025});
  }
  return sets;
}

TEST(KinematicTable, EveryEntryIsTheCappedExactCostForEveryHeadingAndDirection) {
  for (NamedConfig& set : primitiveSets()) {
    set.config.heuristics.kinematic_radius =
        12 * set.resolution;  // R = 12 cells: quick, and every kind of entry
    // The table does not depend on the map; the map only has to hold the robot (0.4 m wide),
    // which the lattice checks: 24 cells of 0.025 m.
    auto map = std::make_shared<GridMap>();
    map->width = map->height = 24;
    map->resolution = set.resolution;
    map->cost.assign(24 * 24, kFreeCost);
    const LatticeGraph g(map, set.config);
    ASSERT_TRUE(g.kinematicTables()) << set.name;
    const KinematicTables& t = *g.kinematicTables();
    ASSERT_EQ(t.radius(), 12) << set.name;
    const std::vector<KinematicMove> moves = movesOf(g);
    int capped = 0, exact = 0;
    for (const Direction dir : {Direction::kToGoal, Direction::kFromStart}) {
      std::vector<int> headings;
      for (int h = 0; h < g.numHeadings(); ++h) headings.push_back(h);
      headings.push_back(kAnyHeading);
      for (const int heading : headings) {
        const KinematicLookup lookup = t.lookup(dir, heading);
        ASSERT_TRUE(lookup.valid());
        const EmptyLatticeCosts e =
            emptyLatticeCosts(moves, g.numHeadings(), 2 * t.radius() + 2, dir, heading);
        std::string first;
        EXPECT_EQ(mismatches(lookup, e, t, &first), 0)
            << set.name << (dir == Direction::kToGoal ? " to goal" : " from start") << " heading "
            << heading << ": first " << first;
        for (int h = 0; h < g.numHeadings(); ++h) {
          const double gcap = std::floor(t.costPerCell() * (2.0 * t.radius() - 9.0));
          const Cost tv = e.at(9, 0, h);
          (tv > gcap ? capped : exact) += 1;
        }
      }
    }
    EXPECT_GT(capped, 0) << set.name << ": the cap never applied at 9 cells out";
    EXPECT_GT(exact, 0) << set.name << ": no exact entry at 9 cells out";
    // Symmetric sets need fewer slices than headings (16 headings: 3 orbits).
    if (std::string(set.name).rfind("generated", 0) == 0) {
      EXPECT_EQ(t.numSymmetries(), 8) << set.name;
    }
  }
}

// Cheapest cost from each state to t, by a Dijkstra over the graph's own (reversed) edges.
std::vector<Cost> costsTo(const LatticeGraph& g, const LatticeState& t) {
  const int w = g.width(), nh = g.numHeadings();
  std::vector<Cost> dist(static_cast<std::size_t>(w) * g.height() * nh, kInfiniteCost);
  auto index = [&](int x, int y, int h) { return (static_cast<std::size_t>(y) * w + x) * nh + h; };
  using Item = std::pair<Cost, std::tuple<int, int, int>>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  dist[index(t.x, t.y, t.heading)] = 0;
  q.push({0, {t.x, t.y, t.heading}});
  while (!q.empty()) {
    const auto [cst, st] = q.top();
    q.pop();
    const auto [x, y, h] = st;
    if (cst != dist[index(x, y, h)]) continue;
    for (const LatticeAction* a : g.actionsInto(h)) {
      const int px = x - a->dx, py = y - a->dy;
      const Cost e = g.edgeCost(px, py, *a);
      if (e == kInvalidEdge) continue;
      const std::size_t j = index(px, py, a->start_heading);
      if (cst + e < dist[j]) {
        dist[j] = cst + e;
        q.push({dist[j], {px, py, a->start_heading}});
      }
    }
  }
  return dist;
}

// A planner's anchor (with the table) on real and generated maps: consistent on every edge,
// h(goal) = 0, and never above the exact cost-to-go (a Dijkstra over the map's own lattice).
TEST(KinematicTable, AnchorConsistentAndAdmissibleAcrossTheDiscEdge) {
  int crossing = 0, edges = 0;
  for (unsigned seed = 1; seed <= 6; ++seed) {
    const auto map = test::randomMap(40, 36, 0.05, seed + 70, 4, seed % 2 ? 120 : 0);
    LatticeConfig c;
    c.motion.turning_radius = 0.2;
    c.motion.turn_in_place = seed % 3 != 0;
    c.motion.allow_reverse = seed % 3 == 2;
    c.robot.footprint = test::rectangle(0.08, 0.05);
    c.cost.penalty = seed % 2 ? 3.0 : 1.0;
    c.heuristics.kinematic_radius = 0.05 * (6 + seed);  // a small disc: many edges cross its edge
    c.heuristics.coarse_anchor = seed % 2 == 0;
    c.heuristics.anchor_connectivity = seed % 4 == 1 ? 8 : 16;
    const LatticeGraph g(map, c);
    const HeuristicGridBuilder b(g);
    // A goal that many states can reach (a forward-only robot facing a wall has few).
    std::mt19937 rng(seed);
    LatticeState t{0, 0, 0};
    std::vector<Cost> dist;
    for (int reach = 0; reach < 500;) {
      t = {static_cast<int>(rng() % 40), static_cast<int>(rng() % 36),
           static_cast<int>(rng() % g.numHeadings())};
      if (!g.stateValid(t.x, t.y, t.heading)) continue;
      dist = costsTo(g, t);
      reach = static_cast<int>(
          std::count_if(dist.begin(), dist.end(), [](Cost c) { return c != kInfiniteCost; }));
    }
    for (const bool backward : {false, true}) {
      const auto dir = backward ? Direction::kFromStart : Direction::kToGoal;
      const KinematicLookup k = g.kinematicTables()->lookup(dir, t.heading);
      const int r2 = k.radius() * k.radius();
      // Searching backward the "goal" of the problem is the lattice start t.
      LatticeProblem p(g, b.compute(t.x, t.y, t.heading, false, 1, backward), t, t, 0, backward,
                       false, k);
      std::vector<Edge> succ;
      for (int y = 0; y < 36; ++y) {
        for (int x = 0; x < 40; ++x) {
          for (int h = 0; h < g.numHeadings(); ++h) {
            if (!g.stateValid(x, y, h)) continue;
            const StateId u = p.id(x, y, h);
            HeuristicValue hu = 0, hv = 0;
            p.heuristics(u, &hu, 1);
            p.successors(u, succ);
            for (const Edge& e : succ) {
              p.heuristics(e.to, &hv, 1);
              if (hu == kInfiniteHeuristic || hv == kInfiniteHeuristic) continue;
              ASSERT_LE(static_cast<Cost>(hu), e.cost + static_cast<Cost>(hv))
                  << "seed " << seed << (backward ? " backward" : "") << " at (" << x << ", " << y
                  << ", " << h << ")";
              ++edges;
              const LatticeState v = p.state(e.to);
              const int du = (x - t.x) * (x - t.x) + (y - t.y) * (y - t.y);
              const int dv = (v.x - t.x) * (v.x - t.x) + (v.y - t.y) * (v.y - t.y);
              crossing += (du <= r2) != (dv <= r2);
            }
          }
        }
      }
      HeuristicValue h0 = 1;
      p.heuristics(p.id(t.x, t.y, t.heading), &h0, 1);
      EXPECT_EQ(h0, 0u);
    }
    // Admissible: the anchor (forward) never exceeds the exact cost-to-go over the map.
    const int nh = g.numHeadings();
    auto index = [&](int x, int y, int h) {
      return (static_cast<std::size_t>(y) * g.width() + x) * nh + h;
    };
    const KinematicLookup k = g.kinematicTables()->lookup(Direction::kToGoal, t.heading);
    LatticeProblem p(g, b.compute(t.x, t.y, t.heading, false, 1), t, t, 0, false, false, k);
    int finite = 0;
    for (int y = 0; y < 36; ++y) {
      for (int x = 0; x < 40; ++x) {
        for (int h = 0; h < nh; ++h) {
          const Cost exact = dist[index(x, y, h)];
          if (exact == kInfiniteCost) continue;
          ++finite;
          EXPECT_LE(static_cast<Cost>(p.anchor(x, y, h)), exact)
              << "seed " << seed << " (" << x << ", " << y << ", " << h << ")";
        }
      }
    }
    EXPECT_GE(finite, 500) << "seed " << seed;
  }
  EXPECT_GT(edges, 100000);
  EXPECT_GT(crossing, 1000) << "too few edges cross the disc's edge to test it";
}

// The small tables' primitives: 16 headings, turning radius 0.2 m at 5 cm, a disc of
// radius_cells.
LatticeConfig tableConfig(int radius_cells) {
  LatticeConfig c;
  c.motion.turning_radius = 0.2;
  c.heuristics.kinematic_radius = 0.05 * radius_cells;
  return c;
}

// The lattice of `c` on an empty 8 x 8 map at 5 cm (the tables do not depend on the map).
std::unique_ptr<LatticeGraph> emptyLattice(const LatticeConfig& c) {
  auto map = std::make_shared<GridMap>();
  map->width = map->height = 8;
  map->resolution = 0.05;
  map->cost.assign(64, kFreeCost);
  return std::make_unique<LatticeGraph>(map, c);
}

// The edge case the cap exists for: a state just inside the disc, facing away from the goal, has
// a large T; one move takes it outside, where the table says nothing. "T inside, Euclidean
// outside" is then inconsistent on that edge; the capped table is not.
TEST(KinematicTable, TheCapKeepsTheDiscEdgeConsistentWhereTheNaiveTableIsNot) {
  LatticeConfig c = tableConfig(20);
  c.motion.turn_in_place = false;
  const std::unique_ptr<LatticeGraph> lattice = emptyLattice(c);
  const LatticeGraph& g = *lattice;
  const KinematicTables& t = *g.kinematicTables();
  const int R = t.radius();
  const EmptyLatticeCosts exact =
      emptyLatticeCosts(movesOf(g), g.numHeadings(), 3 * R, Direction::kToGoal, 0);
  const KinematicLookup k = t.lookup(Direction::kToGoal, 0);
  const double s = t.costPerCell();
  auto naive = [&](int x, int y, int h) {
    return x * x + y * y <= R * R ? static_cast<double>(exact.at(x, y, h))
                                  : std::floor(s * std::hypot(x, y));
  };
  auto capped = [&](int x, int y, int h) {
    return std::max(std::floor(s * std::hypot(x, y)), static_cast<double>(k.value(x, y, h)));
  };
  int naive_broken = 0, capped_broken = 0;
  for (int y = -R; y <= R; ++y) {
    for (int x = -R; x <= R; ++x) {
      if (x * x + y * y > R * R) continue;
      for (int h = 0; h < g.numHeadings(); ++h) {
        for (const LatticeAction* a = g.actionsBegin(h); a != g.actionsEnd(h); ++a) {
          const int nx = x + a->dx, ny = y + a->dy;
          if (nx * nx + ny * ny <= R * R) continue;  // only the edges that leave the disc
          naive_broken += naive(x, y, h) > a->base_cost + naive(nx, ny, a->end_heading);
          capped_broken += capped(x, y, h) > a->base_cost + capped(nx, ny, a->end_heading);
        }
      }
    }
  }
  EXPECT_GT(naive_broken, 0) << "the naive table should break on edges leaving the disc";
  EXPECT_EQ(capped_broken, 0);
}

// A mutation: one entry raised by one unit. The exactness check above catches it.
TEST(KinematicTable, AnEntryRaisedByOneIsCaught) {
  const std::unique_ptr<LatticeGraph> lattice = emptyLattice(tableConfig(10));
  const LatticeGraph& g = *lattice;
  const KinematicTables& t = *g.kinematicTables();
  auto slice = std::make_shared<KinematicSlice>(*t.buildSlice(Direction::kToGoal, 0, nullptr));
  const EmptyLatticeCosts exact =
      emptyLatticeCosts(movesOf(g), g.numHeadings(), 2 * t.radius() + 2, Direction::kToGoal, 0);
  KinematicLookup lookup = t.lookup(Direction::kToGoal, 0);
  EXPECT_EQ(mismatches(lookup, exact, t, nullptr), 0);
  // Heading 0's table is folded along the x axis: an entry on the axis is read by one state,
  // one off it by that state and its mirror image.
  ASSERT_TRUE(slice->folded());
  auto on_axis = std::make_shared<KinematicSlice>(*slice);
  KinematicTableTestAccess::raise(*on_axis, 3, 0, 5);
  EXPECT_EQ(mismatches(KinematicTableTestAccess::with(lookup, on_axis), exact, t, nullptr), 1);
  KinematicTableTestAccess::raise(*slice, 3, -2, 5);
  const KinematicLookup mutated = KinematicTableTestAccess::with(lookup, slice);
  EXPECT_EQ(mismatches(mutated, exact, t, nullptr), 2);
}

// Folding: the tables of headings that a reflection fixes keep half the disc, the others all
// of it; every entry stays exact (EveryEntryIsTheCappedExactCost... checks each heading).
TEST(KinematicTable, TablesFixedByAReflectionKeepHalfTheDisc) {
  const std::unique_ptr<LatticeGraph> lattice = emptyLattice(tableConfig(20));
  const LatticeGraph& g = *lattice;
  const KinematicTables& t = *g.kinematicTables();
  ASSERT_EQ(g.numHeadings(), 16);
  const KinematicSlice whole(t.radius(), t.numHeadings());
  // Headings 0 (x axis) and 2 (45 degrees) are fixed by a mirror; heading 1 (26.6) by none.
  for (int key : {0, 1, 2}) {
    for (Direction d : {Direction::kToGoal, Direction::kFromStart}) {
      const auto slice = t.buildSlice(d, key, nullptr);
      ASSERT_TRUE(slice);
      EXPECT_EQ(slice->folded(), key != 1) << "heading " << key;
      if (key == 1) {
        EXPECT_EQ(slice->cells(), whole.cells());
      } else {
        // Half the disc plus the mirror line: the x axis for heading 0, y = x for heading 2.
        const int R = t.radius();
        std::size_t line = 0;
        for (int k = -R; k <= R; ++k) line += key == 0 ? 1 : (2 * k * k <= R * R ? 1 : 0);
        EXPECT_EQ(slice->cells(), (whole.cells() + line) / 2) << "heading " << key;
      }
    }
  }
}

TEST(KinematicTable, SharedBetweenPlannersAndBuiltOnce) {
  auto a = test::randomMap(50, 40, 0.05, 3, 6, 0);
  auto b = test::randomMap(50, 40, 0.05, 4, 9, 80);
  LatticeConfig c;
  c.motion.turning_radius = 0.2;
  c.heuristics.kinematic_radius = 0.6;
  LatticePlanner pa(a, c), pb(b, c);
  EXPECT_TRUE(pa.prepareKinematicTables());
  EXPECT_GT(pa.kinematicTableBytes(), 0u);
  EXPECT_EQ(pa.kinematicTableBytes(), pb.kinematicTableBytes())
      << "one set of tables for both maps";
  LatticeConfig other = c;
  other.cost.penalty = 2.0;  // free-cell costs are the same: still shared
  LatticePlanner pc(a, other);
  EXPECT_EQ(pc.kinematicTableBytes(), pa.kinematicTableBytes());
  LatticeConfig turning = c;
  turning.motion.turning_radius = 0.3;  // other primitives: other tables, none built yet
  LatticePlanner pd(a, turning);
  EXPECT_EQ(pd.kinematicTableBytes(), 0u);
}

TEST(KinematicTable, ABuildIsCancellableAndRetried) {
  LatticeConfig c = tableConfig(20);
  c.heuristics.kinematic_radius = 3.0;  // 60 cells: long enough to stop in the middle
  c.cost.time_to_turn_45 = 0.7;         // tables of their own (other costs than the other tests')
  const std::unique_ptr<LatticeGraph> lattice = emptyLattice(c);
  const LatticeGraph& g = *lattice;
  std::atomic<bool> cancel{true};
  const StopCondition stop(&cancel, std::numeric_limits<double>::infinity());
  EXPECT_FALSE(g.kinematicTables()->lookup(Direction::kToGoal, 1, &stop).valid());
  EXPECT_EQ(g.kinematicTables()->slicesBuilt(), 0);
  EXPECT_TRUE(g.kinematicTables()->lookup(Direction::kToGoal, 1).valid());
  EXPECT_EQ(g.kinematicTables()->slicesBuilt(), 1);
}

}  // namespace
}  // namespace lattice
}  // namespace amha
