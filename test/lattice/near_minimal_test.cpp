// The near-minimal generator, for several resolutions, heading counts, radii and motion models:
// exact ends, curvature measured on the poses, every heading served, closed under the lattice
// symmetries, no primitive a composition of shorter ones; the motion models and backward twins.
#include <algorithm>
#include <cmath>
#include <map>
#include <queue>
#include <random>
#include <tuple>

#include <gtest/gtest.h>

#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/lattice/motion_primitives.h"
#include "test_support.h"

namespace amha {
namespace lattice {
namespace {

struct Case {
  double resolution;
  int headings;
  double radius;
  MotionModel model;
  bool reverse;
};

const Case kCases[] = {
    {0.05, 16, 0.5, MotionModel::kAckermann, false},
    {0.05, 16, 0.5, MotionModel::kDifferential, true},
    {0.1, 8, 0.3, MotionModel::kOmni, false},
    {0.025, 32, 0.4, MotionModel::kAckermann, true},
    {0.05, 24, 1.0, MotionModel::kDifferential, false},
    {0.1, 16, 0.25, MotionModel::kAckermann, false},
};

PrimitiveGeneratorOptions optionsFor(const Case& c) {
  PrimitiveGeneratorOptions o;
  o.resolution = c.resolution;
  o.num_headings = c.headings;
  o.turning_radius = c.radius;
  o.motion_model = c.model;
  o.allow_reverse = c.reverse;
  return o;
}

bool moves(const MotionPrimitive& p) { return p.end_dx != 0 || p.end_dy != 0; }
// Drives forward along its heading (not a turn on the spot, a sideways or a backward move).
bool forward(const PrimitiveSet& s, const MotionPrimitive& p) {
  if (!moves(p) || p.reverse) return false;
  const double dx = p.poses[1].x, dy = p.poses[1].y, phi = s.heading_angles[p.start_heading];
  return dx * std::cos(phi) + dy * std::sin(phi) > 0.5 * std::hypot(dx, dy);
}
double length(const MotionPrimitive& p) { return p.arc_length + p.straight_length; }

TEST(NearMinimalGenerator, ExactEndsBoundedCurvatureEveryHeading) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(std::to_string(c.headings) + " headings, radius " + std::to_string(c.radius));
    const PrimitiveSet s = generateNearMinimalPrimitives(optionsFor(c));
    ASSERT_EQ(s.num_headings, c.headings);
    const double res = c.resolution;
    for (int h = 0; h < s.num_headings; ++h) {
      const auto r = s.range(h);
      ASSERT_GT(r.second, r.first) << "heading " << h << " has no primitives";
      int straights = 0, turns_left = 0, turns_right = 0;
      for (std::size_t i = r.first; i < r.second; ++i) {
        const MotionPrimitive& p = s.primitives[i];
        // Exact ends: the first pose is the start state, the last the end state, to the bit.
        EXPECT_EQ(p.poses.front().x, 0.0);
        EXPECT_EQ(p.poses.front().y, 0.0);
        EXPECT_EQ(p.poses.front().theta, s.heading_angles[h]);
        EXPECT_EQ(p.poses.back().x, p.end_dx * res);
        EXPECT_EQ(p.poses.back().y, p.end_dy * res);
        EXPECT_EQ(p.poses.back().theta, s.heading_angles[p.end_heading]);
        for (std::size_t k = 1; k < p.poses.size(); ++k) {
          const Pose2D &a = p.poses[k - 1], &b = p.poses[k];
          const double d = std::hypot(b.x - a.x, b.y - a.y);
          EXPECT_LE(d, res + 1e-9) << "poses more than a cell apart";
          // Curvature on the poses: between two poses d apart the heading turns at most as much
          // as on a circle of radius r_min through both, 2 asin(d / 2 r_min) (turns on the spot
          // excepted), and three consecutive points lie on a circle of radius >= r_min.
          if (moves(p)) {
            EXPECT_LE(angleDistance(a.theta, b.theta),
                      2.0 * std::asin(std::min(1.0, d / (2.0 * c.radius))) * (1 + 1e-6) + 1e-9);
          }
          if (k >= 2 && moves(p)) {
            const Pose2D& z = p.poses[k - 2];
            const double cross = (a.x - z.x) * (b.y - z.y) - (a.y - z.y) * (b.x - z.x);
            const double abc = std::hypot(a.x - z.x, a.y - z.y) * std::hypot(b.x - a.x, b.y - a.y) *
                               std::hypot(b.x - z.x, b.y - z.y);
            if (abc > 0.0) {
              EXPECT_LE(2.0 * std::fabs(cross) / abc, 1.001 / c.radius) << "primitive " << i;
            }
          }
        }
        if (forward(s, p) && p.end_heading == h) ++straights;
        if (forward(s, p) && p.turning_radius > 0.0) ++turns_left;
        if (forward(s, p) && p.turning_radius < 0.0) ++turns_right;
        if (p.turning_radius != 0.0) {
          EXPECT_GE(std::fabs(p.turning_radius), c.radius * (1 - 1e-9));
        }
      }
      EXPECT_EQ(straights, 1) << "heading " << h << ": one straight (longer ones are compositions)";
      EXPECT_GE(turns_left, 1) << "heading " << h;
      EXPECT_GE(turns_right, 1) << "heading " << h;
    }
  }
}

// The 8 symmetries of the square lattice, as maps of vectors and angles.
struct Sym {
  bool reflect;
  int quarter;
  void apply(double& x, double& y, double& th) const {
    if (reflect) {
      std::swap(x, y);
      th = M_PI / 2 - th;
    }
    for (int q = 0; q < quarter; ++q) {
      const double t = x;
      x = -y;
      y = t;
    }
    th = normalizeAngle(th + quarter * M_PI / 2);
  }
};

TEST(NearMinimalGenerator, ClosedUnderTheLatticeSymmetries) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(std::to_string(c.headings) + " headings, radius " + std::to_string(c.radius));
    const PrimitiveSet s = generateNearMinimalPrimitives(optionsFor(c));
    std::map<std::tuple<int, int, int, int, bool>, const MotionPrimitive*> index;
    for (const MotionPrimitive& p : s.primitives) {
      EXPECT_TRUE(
          index.insert({{p.start_heading, p.end_dx, p.end_dy, p.end_heading, p.reverse}, &p})
              .second)
          << "two primitives from heading " << p.start_heading << " to the same state";
    }
    for (int reflect = 0; reflect < 2; ++reflect) {
      for (int quarter = 0; quarter < 4; ++quarter) {
        const Sym g{reflect == 1, quarter};
        for (const MotionPrimitive& p : s.primitives) {
          double sx = 0, sy = 0, sth = s.heading_angles[p.start_heading];
          double ex = p.end_dx, ey = p.end_dy, eth = s.heading_angles[p.end_heading];
          g.apply(sx, sy, sth);
          g.apply(ex, ey, eth);
          const int h0 = s.headingIndex(sth), h1 = s.headingIndex(eth);
          const auto it = index.find({h0, static_cast<int>(std::lround(ex)),
                                      static_cast<int>(std::lround(ey)), h1, p.reverse});
          ASSERT_NE(it, index.end())
              << "the image of a primitive of heading " << p.start_heading << " is missing";
          const MotionPrimitive& q = *it->second;
          ASSERT_EQ(q.poses.size(), p.poses.size());
          for (std::size_t k = 0; k < p.poses.size(); ++k) {
            double x = p.poses[k].x, y = p.poses[k].y, th = p.poses[k].theta;
            g.apply(x, y, th);
            EXPECT_NEAR(q.poses[k].x, x, 1e-9);
            EXPECT_NEAR(q.poses[k].y, y, 1e-9);
            EXPECT_NEAR(angleDistance(q.poses[k].theta, th), 0.0, 1e-9);
          }
        }
      }
    }
  }
}

// The cheapest sequence of the given primitives from (0, 0, h0) to (x, y, h1), if it costs at
// most `bound` (A* with the straight-line distance; lengths in metres).
double composedLength(const PrimitiveSet& s, const std::vector<const MotionPrimitive*>& usable,
                      int h0, int x, int y, int h1, double bound) {
  std::vector<std::vector<const MotionPrimitive*>> from(s.num_headings);
  for (const MotionPrimitive* p : usable) from[p->start_heading].push_back(p);
  using State = std::tuple<int, int, int>;
  std::map<State, double> g;
  using Item = std::pair<double, State>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
  auto h = [&](int cx, int cy) { return std::hypot(cx - x, cy - y) * s.resolution; };
  g[{0, 0, h0}] = 0.0;
  open.push({h(0, 0), {0, 0, h0}});
  while (!open.empty()) {
    const auto [f, st] = open.top();
    open.pop();
    const auto [cx, cy, ch] = st;
    const double gc = g[st];
    if (f > gc + h(cx, cy) + 1e-12) continue;
    if (cx == x && cy == y && ch == h1) return gc;
    for (const MotionPrimitive* p : from[ch]) {
      const State next{cx + p->end_dx, cy + p->end_dy, p->end_heading};
      const double ng = gc + length(*p);
      if (ng + h(cx + p->end_dx, cy + p->end_dy) > bound) continue;
      const auto it = g.find(next);
      if (it != g.end() && it->second <= ng) continue;
      g[next] = ng;
      open.push({ng + h(cx + p->end_dx, cy + p->end_dy), next});
    }
  }
  return INFINITY;
}

TEST(NearMinimalGenerator, NoPrimitiveIsACompositionOfShorterOnes) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(std::to_string(c.headings) + " headings, radius " + std::to_string(c.radius));
    const PrimitiveGeneratorOptions o = optionsFor(c);
    const PrimitiveSet s = generateNearMinimalPrimitives(o);
    std::vector<const MotionPrimitive*> moving;
    for (const MotionPrimitive& p : s.primitives) {
      if (forward(s, p)) moving.push_back(&p);
    }
    for (const MotionPrimitive* p : moving) {
      if (p->start_heading > c.headings / 8) continue;  // the others are their images
      std::vector<const MotionPrimitive*> shorter;
      for (const MotionPrimitive* q : moving) {
        if (length(*q) < length(*p) - 1e-9) shorter.push_back(q);
      }
      const double bound = (1.0 + o.tolerance) * length(*p);
      EXPECT_GT(
          composedLength(s, shorter, p->start_heading, p->end_dx, p->end_dy, p->end_heading, bound),
          bound)
          << "the primitive of heading " << p->start_heading << " to (" << p->end_dx << ", "
          << p->end_dy << ", " << p->end_heading << ") is a composition of shorter ones";
    }
  }
}

TEST(NearMinimalGenerator, MotionModelsAndBackwardTwins) {
  PrimitiveGeneratorOptions o;
  o.motion_model = MotionModel::kAckermann;
  const PrimitiveSet ackermann = generateNearMinimalPrimitives(o);
  EXPECT_EQ(ackermann.motion_model, "ackermann");
  for (const MotionPrimitive& p : ackermann.primitives) EXPECT_TRUE(moves(p));
  o.motion_model = MotionModel::kDifferential;
  const PrimitiveSet diff = generateNearMinimalPrimitives(o);
  EXPECT_EQ(diff.motion_model, "diff");
  EXPECT_EQ(diff.primitives.size(),
            ackermann.primitives.size() + 2 * 16);  // turns on the spot to both sides
  o.turn_in_place = false;
  EXPECT_EQ(generateNearMinimalPrimitives(o).primitives.size(), ackermann.primitives.size());
  o.turn_in_place = true;
  o.motion_model = MotionModel::kOmni;
  const PrimitiveSet omni = generateNearMinimalPrimitives(o);
  EXPECT_EQ(omni.motion_model, "omni");
  EXPECT_EQ(omni.primitives.size(), diff.primitives.size() + 2 * 16);  // one slide to each side
  int sideways = 0;
  for (const MotionPrimitive& p : omni.primitives) {
    const double phi = omni.heading_angles[p.start_heading];
    if (moves(p) && std::fabs(p.end_dx * std::cos(phi) + p.end_dy * std::sin(phi)) < 1e-9) {
      ++sideways;
      for (const Pose2D& q : p.poses) EXPECT_EQ(q.theta, phi);
    }
  }
  EXPECT_EQ(sideways, 2 * 16);

  o.motion_model = MotionModel::kAckermann;
  o.allow_reverse = true;
  o.reverse_multiplier = 2.5;
  const PrimitiveSet both = generateNearMinimalPrimitives(o);
  ASSERT_EQ(both.primitives.size(), 2 * ackermann.primitives.size());
  for (const MotionPrimitive& p : both.primitives) {
    if (!p.reverse) continue;
    EXPECT_DOUBLE_EQ(p.cost_multiplier, 2.5);
    // It drives backwards: its first step is opposite to its heading.
    const double phi = both.heading_angles[p.start_heading];
    EXPECT_LT(p.poses[1].x * std::cos(phi) + p.poses[1].y * std::sin(phi), 0.0);
  }
}

TEST(NearMinimalGenerator, RefusesBadOptions) {
  PrimitiveGeneratorOptions o;
  o.tolerance = -0.1;
  EXPECT_THROW(generateNearMinimalPrimitives(o), LatticeError);
  o = PrimitiveGeneratorOptions();
  o.tolerance = NAN;
  EXPECT_THROW(generateNearMinimalPrimitives(o), LatticeError);
  o = PrimitiveGeneratorOptions();
  o.num_headings = 12;
  EXPECT_THROW(generateNearMinimalPrimitives(o), LatticeError);
  o = PrimitiveGeneratorOptions();
  o.turning_radius = 100.0;  // 2000 cells: the tables would not fit
  try {
    generateNearMinimalPrimitives(o);
    ADD_FAILURE();
  } catch (const LatticeError& e) {
    EXPECT_NE(std::string(e.what()).find("legacy"), std::string::npos) << e.what();
  }
  o = PrimitiveGeneratorOptions();
  o.generator = PrimitiveGenerator::kLegacy;
  o.motion_model = MotionModel::kOmni;
  EXPECT_THROW(generatePrimitives(o), LatticeError);
}

// On generated maps, A*'s optimum with the near-minimal set is never worse than with the legacy
// set (for the same robot) by more than rounding, and strictly better on some queries.
TEST(NearMinimalGenerator, OptimaNeverWorseThanTheLegacySetsAndSometimesBetter) {
  int compared = 0, better = 0;
  for (unsigned seed = 1; seed <= 6; ++seed) {
    auto map = test::randomMap(90, 90, 0.05, seed, 14, seed % 2 ? 100 : 0);
    LatticeConfig c;
    c.robot.radius = 0.08;
    c.motion.turning_radius = 0.3;
    c.motion.model = seed % 3 == 0 ? MotionModel::kDifferential : MotionModel::kAckermann;
    c.cost.penalty = 1.0;
    LatticeConfig legacy_config = c;
    legacy_config.motion.generator = PrimitiveGenerator::kLegacy;
    LatticePlanner fresh(map, c), legacy(map, legacy_config);
    const LatticeGraph graph(map, c);
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> rx(0, map->width - 1), ry(0, map->height - 1),
        rh(0, graph.numHeadings() - 1);
    for (int q = 0, tries = 0; q < 4 && tries < 2000; ++tries) {
      const int sx = rx(rng), sy = ry(rng), sh = rh(rng), gx = rx(rng), gy = ry(rng), gh = rh(rng);
      if (!graph.stateValid(sx, sy, sh) || !graph.stateValid(gx, gy, gh) ||
          std::hypot(gx - sx, gy - sy) < 30)
        continue;
      ++q;
      const Pose2D start = graph.stateToPose(sx, sy, sh), goal = graph.stateToPose(gx, gy, gh);
      const PlanResult a =
          fresh.plan(start, goal, defaultConfig(Algorithm::kAStar), SearchLimits());
      const PlanResult b =
          legacy.plan(start, goal, defaultConfig(Algorithm::kAStar), SearchLimits());
      ASSERT_NE(a.search.status, SearchStatus::kTimeLimit);
      if (b.solutions.empty()) continue;  // legacy finds no path: nothing to compare
      ASSERT_FALSE(a.solutions.empty())
          << "seed " << seed << ": the legacy set finds a path, the new one none";
      // Each of the legacy path's primitives may cost a unit more when composed of shorter ones
      // (costs are rounded up per primitive), and two for the cell-cost penalty's rounding.
      const Solution& x = a.solutions.back().search;
      const Solution& y = b.solutions.back().search;
      const Cost slack = 3 * static_cast<Cost>(y.path.size());
      EXPECT_LE(x.cost, y.cost + slack) << "seed " << seed << " query " << q;
      ++compared;
      better += x.cost + slack < y.cost;
    }
  }
  EXPECT_GE(compared, 12);
  EXPECT_GE(better, 1) << "the new set was never strictly better on " << compared << " queries";
}

TEST(PrimitiveNames, GeneratorsAndMotionModelsParseOnlyTheirNames) {
  PrimitiveGenerator g = PrimitiveGenerator::kNearMinimal;
  EXPECT_TRUE(parsePrimitiveGenerator("legacy", &g));
  EXPECT_EQ(g, PrimitiveGenerator::kLegacy);
  EXPECT_TRUE(parsePrimitiveGenerator("near-minimal", &g));
  EXPECT_EQ(g, PrimitiveGenerator::kNearMinimal);
  EXPECT_FALSE(parsePrimitiveGenerator("Legacy", &g));
  EXPECT_FALSE(parsePrimitiveGenerator("prims.mprim", &g));
  EXPECT_EQ(g, PrimitiveGenerator::kNearMinimal);  // unchanged when refused
  MotionModel m = MotionModel::kDifferential;
  for (MotionModel each :
       {MotionModel::kDifferential, MotionModel::kAckermann, MotionModel::kOmni}) {
    EXPECT_TRUE(parseMotionModel(motionModelName(each), &m));
    EXPECT_EQ(m, each);
  }
  EXPECT_FALSE(parseMotionModel("car", &m));
}

}  // namespace
}  // namespace lattice
}  // namespace amha
