// Limits of the lattice planner: a 4000 x 4000 map, a memory cap on a big open map, huge or
// negative sizes in maps and files, a cancel or deadline while a new goal's heuristic grids are
// computed, and plan() called from several threads at once on one planner, with cancels.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <climits>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/lattice/map_loaders.h"
#include "amha_planner/lattice/motion_primitives.h"
#include "path_validator.h"
#include "test_support.h"

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define AMHA_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define AMHA_SANITIZED 1
#endif
#endif
#ifndef AMHA_SANITIZED
#define AMHA_SANITIZED 0
#endif

namespace amha {
namespace lattice {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// A cancel or deadline is typically seen within a few milliseconds (the checks run every 4096
// cells); the bounds leave room for a loaded 2-core machine and for the sanitizers' slowdown,
// and are still far below the grids' full time (~1 s on 2000 x 2000, ~1-3 s on 4000 x 4000).
constexpr double kLatencyBound = AMHA_SANITIZED ? 1.0 : 0.25;
// A setup refused up front (before it allocates or builds anything that takes seconds); TSan
// once took 0.127 s for what takes a few ms unsanitised.
constexpr double kRefusalBound = AMHA_SANITIZED ? 0.5 : 0.1;

// A /proc/self/status field in kB (VmRSS: now; VmHWM: peak since the last resetPeakRss()).
long statusKb(const char* key) {
  std::ifstream f("/proc/self/status");
  for (std::string line; std::getline(f, line);) {
    if (line.rfind(key, 0) == 0) return std::stol(line.substr(line.find(':') + 1));
  }
  return -1;
}
// Linux >= 4.0: writing 5 to clear_refs resets the peak RSS (VmHWM) to the current RSS.
bool resetPeakRss() {
  std::ofstream f("/proc/self/clear_refs");
  f << "5";
  f.flush();
  return static_cast<bool>(f);
}

// An n x n map at 0.05 m with 20 x 20-cell blocks on ~10% of it and a clear square in the middle.
std::shared_ptr<GridMap> bigMap(int n, unsigned seed) {
  auto map = std::make_shared<GridMap>();
  map->width = map->height = n;
  map->resolution = 0.05;
  map->cost.assign(static_cast<std::size_t>(n) * n, kFreeCost);
  std::mt19937 rng(seed);
  for (int k = 0; k < n / 4 * (n / 1000 + 1) * (n / 1000 + 1); ++k) {
    const int x0 = static_cast<int>(rng() % n), y0 = static_cast<int>(rng() % n);
    for (int y = y0; y < std::min(n, y0 + 20); ++y) {
      std::fill_n(map->cost.begin() + static_cast<std::ptrdiff_t>(y) * n + x0, std::min(20, n - x0),
                  kLethalCost);
    }
  }
  for (int y = n / 2 - 60; y < n / 2 + 60; ++y) {
    std::fill_n(map->cost.begin() + static_cast<std::ptrdiff_t>(y) * n + n / 2 - 60, 120,
                kFreeCost);
  }
  return map;
}

// Every pose of the path: the footprint (in cells) meets no lethal or unknown cell.
::testing::AssertionResult posesCollisionFree(const LatticePlanner& planner,
                                              const std::vector<Pose2D>& poses) {
  const GridMap& m = planner.map();
  for (std::size_t k = 0; k < poses.size(); ++k) {
    std::vector<std::array<double, 2>> poly = planner.footprintAt(poses[k]);
    double minx = 1e18, maxx = -1e18, miny = 1e18, maxy = -1e18;
    for (auto& v : poly) {
      v = {(v[0] - m.origin_x) / m.resolution,
           (v[1] - m.origin_y) / m.resolution};  // origin_yaw is 0 here
      minx = std::min(minx, v[0]);
      maxx = std::max(maxx, v[0]);
      miny = std::min(miny, v[1]);
      maxy = std::max(maxy, v[1]);
    }
    for (int j = static_cast<int>(std::floor(miny)) - 1;
         j <= static_cast<int>(std::floor(maxy)) + 1; ++j) {
      for (int i = static_cast<int>(std::floor(minx)) - 1;
           i <= static_cast<int>(std::floor(maxx)) + 1; ++i) {
        const bool blocked =
            i < 0 || j < 0 || i >= m.width || j >= m.height || m.at(i, j) >= kLethalCost;
        if (blocked && test::polygonMeetsSquare(poly, i, j, 0.0)) {
          return ::testing::AssertionFailure()
                 << "pose " << k << " touches cell (" << i << ", " << j << ")";
        }
      }
    }
  }
  return ::testing::AssertionSuccess();
}

// ---------------------------------------------------------------------------------------------
// Big maps.

// 4000 x 4000 cells (200 m x 200 m at 0.05 m): the planner builds, a cancel while a new goal's
// grids are computed is answered within milliseconds, and a short query plans; times and
// memory are printed (docs/results/robustness.md quotes them).
TEST(LatticeLimits, Map4000x4000BuildsCancelsGridsAndPlansAShortQuery) {
  const int n = 4000;
  resetPeakRss();
  const long rss0 = statusKb("VmRSS");
  auto map = bigMap(n, 1);
  auto t0 = Clock::now();
  LatticePlanner planner(map, LatticeConfig());
  const double build_s = secondsSince(t0);
  const long build_hwm = statusKb("VmHWM");
  const double c = n / 2 * 0.05;

  // A cancel 30 ms into the grids of a new goal.
  std::atomic<bool> cancel{false};
  SearchLimits limits;
  limits.cancel = &cancel;
  PlanResult cancelled;
  std::thread t([&] {
    cancelled = planner.plan({c, c, 0.0}, {c - 2.0, c + 1.5, 0.0},
                             defaultConfig(Algorithm::kAmhaStar), limits);
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  const auto t_cancel = Clock::now();
  cancel = true;
  t.join();
  const double cancel_latency_s = secondsSince(t_cancel);
  EXPECT_EQ(cancelled.error, QueryError::kNone) << cancelled.message;
  EXPECT_EQ(cancelled.search.status, SearchStatus::kCancelled);
  EXPECT_TRUE(cancelled.solutions.empty());
  EXPECT_LT(cancel_latency_s, kLatencyBound);

  // A short query (2.2 m) with a generous budget.
  limits = SearchLimits();
  limits.time_limit_s = 60.0;
  t0 = Clock::now();
  const Pose2D start{c, c, 0.0}, goal{c + 2.0, c + 1.0, M_PI / 2};
  const PlanResult r = planner.plan(start, goal, defaultConfig(Algorithm::kAmhaStar), limits);
  const double plan_s = secondsSince(t0);
  ASSERT_EQ(r.error, QueryError::kNone) << r.message;
  ASSERT_FALSE(r.solutions.empty()) << statusName(r.search.status);
  const std::vector<Pose2D>& poses = r.solutions.back().poses;
  EXPECT_NEAR(poses.front().x, start.x, 0.05);
  EXPECT_NEAR(poses.back().x, goal.x, 0.05);
  EXPECT_NEAR(poses.back().y, goal.y, 0.05);
  EXPECT_TRUE(posesCollisionFree(planner, poses));
  const long hwm = statusKb("VmHWM");
  std::cout << "[ limits   ] 4000 x 4000: build " << build_s << " s (peak RSS +"
            << (build_hwm - rss0) / 1024 << " MB), cancel during the grids answered in "
            << cancel_latency_s * 1000 << " ms, short query " << plan_s << " s (grids "
            << r.heuristic_seconds << " s, search " << r.search.elapsed_s << " s, "
            << r.solutions.size() << " solutions, " << statusName(r.search.status)
            << "), peak RSS +" << (hwm - rss0) / 1024 << " MB" << std::endl;
  RecordProperty("build_ms", static_cast<int>(build_s * 1000));
  RecordProperty("cancel_latency_ms", static_cast<int>(cancel_latency_s * 1000));
  RecordProperty("plan_ms", static_cast<int>(plan_s * 1000));
  RecordProperty("peak_rss_mb", static_cast<int>((hwm - rss0) / 1024));
  if (!AMHA_SANITIZED && rss0 > 0 && hwm > 0) {
    EXPECT_LT(hwm - rss0, 1536L * 1024) << "kB above the start";
  }
}

// A search that would need far more memory than allowed ends with the memory-cap status (and
// its memory stays near the cap) instead of growing until the OOM killer ends the process:
// 2000 x 2000 open cells, a goal walled in, and the Euclidean anchor, so the search would
// have to generate all 64 M states to prove the goal unreachable. The wall encloses 400 x 400
// cells (2.6 M states), more than SearchProblem::goalUnreachable may look at: the goal's side
// cannot prove it either.
TEST(LatticeLimits, MemoryCapEndsASearchOnABigOpenMap) {
  const int n = 2000;
  auto map = std::make_shared<GridMap>();
  map->width = map->height = n;
  map->resolution = 0.05;
  map->cost.assign(static_cast<std::size_t>(n) * n, kFreeCost);
  const int gx = 1500, gy = 1500;
  const int r = 200;
  for (int k = -r; k <= r; ++k) {  // a closed ring of lethal cells around the goal
    map->cost[static_cast<std::size_t>(gy - r) * n + gx + k] = kLethalCost;
    map->cost[static_cast<std::size_t>(gy + r) * n + gx + k] = kLethalCost;
    map->cost[static_cast<std::size_t>(gy + k) * n + gx - r] = kLethalCost;
    map->cost[static_cast<std::size_t>(gy + k) * n + gx + r] = kLethalCost;
  }
  LatticeConfig config;
  config.heuristics.grid_anchor = false;  // the Euclidean anchor cannot see the wall
  config.heuristics.num_inadmissible = 0;
  LatticePlanner planner(map, config);
  for (Algorithm a : {Algorithm::kAStar, Algorithm::kAraStar}) {
    SearchLimits limits;
    limits.max_memory_bytes = std::size_t{64} << 20;
    limits.time_limit_s = 120.0;
    resetPeakRss();
    const long rss0 = statusKb("VmRSS");
    const auto t0 = Clock::now();
    const PlanResult r = planner.plan(
        {10.0, 10.0, 0.0}, {(gx + 0.5) * 0.05, (gy + 0.5) * 0.05, 0.0}, defaultConfig(a), limits);
    const double s = secondsSince(t0);
    const long grown = statusKb("VmHWM") - rss0;
    ASSERT_EQ(r.error, QueryError::kNone) << r.message;
    EXPECT_EQ(r.search.status, SearchStatus::kMemoryLimit)
        << algorithmName(a) << ": " << statusName(r.search.status);
    EXPECT_TRUE(r.solutions.empty());
    // The search checks the domain's memory every 4096 expansions, and the domain's arrays grow
    // in between: it may end a little above the cap.
    EXPECT_LE(r.search.peak_memory_bytes, limits.max_memory_bytes + limits.max_memory_bytes / 8)
        << algorithmName(a);
    EXPECT_GT(r.search.peak_memory_bytes, limits.max_memory_bytes / 2)
        << "stopped long before the cap";
    std::cout << "[ limits   ] " << algorithmName(a)
              << " with a 64 MB cap: " << statusName(r.search.status) << " after " << s << " s, "
              << r.search.expansions << " expansions, " << r.search.peak_states
              << " states, counted " << r.search.peak_memory_bytes / (1 << 20) << " MB, peak RSS +"
              << grown / 1024 << " MB" << std::endl;
    if (!AMHA_SANITIZED && rss0 > 0) {
      EXPECT_LT(grown, 2 * 64L * 1024 + 32 * 1024) << "kB: memory not bounded by the cap";
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Huge or negative sizes.

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const LatticeError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(LatticeLimits, HugeOrNegativeSizesInMapsAreRefused) {
  const std::int8_t cells[4] = {0, 0, 0, 0};
  const OccupancyConversion conv;
  auto occ = [&](int w, int h, std::size_t size, double res = 0.05) {
    return errorOf([&] { gridMapFromOccupancy(w, h, res, 0, 0, 0, cells, size, conv); });
  };
  EXPECT_NE(occ(-1, 4, 4).find("size -1 x 4 is not positive"), std::string::npos);
  EXPECT_NE(occ(4, INT_MIN, 4).find("is not positive"), std::string::npos);
  EXPECT_NE(occ(0, 0, 0).find("is not positive"), std::string::npos);
  EXPECT_NE(occ(INT_MAX, INT_MAX, 4).find("exceeds the limit"), std::string::npos);
  EXPECT_NE(occ(65536, 65536, 4).find("4294967296 cells exceeds the limit of 67108864"),
            std::string::npos);
  EXPECT_NE(occ(2, 2, 3).find("data has 3 values, width x height is 4"), std::string::npos);
  EXPECT_NE(occ(2, 2, 4, -0.05).find("resolution -0.05 is not positive"), std::string::npos);
  EXPECT_NE(occ(2, 2, 4, std::nan("")).find("is not positive and finite"), std::string::npos);
  EXPECT_NE(occ(2, 2, 4, INFINITY).find("is not positive and finite"), std::string::npos);

  // A GridMap built by hand with a bad size.
  auto bad = std::make_shared<GridMap>();
  bad->width = -3;
  bad->height = 5;
  bad->resolution = 0.05;
  EXPECT_NE(errorOf([&] { LatticePlanner p(bad, LatticeConfig()); }).find("is not positive"),
            std::string::npos);
  bad->width = 3;
  bad->cost.assign(14, 0);
  EXPECT_NE(errorOf([&] { LatticePlanner p(bad, LatticeConfig()); }).find("does not match"),
            std::string::npos);
}

TEST(LatticeLimits, HugeOrNegativeSizesInFilesAreRefused) {
  const std::string dir = test::tempDir();
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir + "/" + name) << text;
    return dir + "/" + name;
  };
  // Moving AI .map headers.
  auto movingai = [&](const std::string& header) {
    return errorOf(
        [&] { loadMovingAiMap(write("m.map", "type octile\n" + header + "map\n"), 0.1, 1); });
  };
  EXPECT_NE(movingai("height 2000000\nwidth 4\n").find("height 2000000 is not in 1..1000000"),
            std::string::npos);
  EXPECT_NE(movingai("height -5\nwidth 4\n").find("height -5 is not in 1..1000000"),
            std::string::npos);
  EXPECT_NE(movingai("height 99999999999999999999999\nwidth 4\n").find("expected 'height N'"),
            std::string::npos);
  EXPECT_NE(movingai("height 100000\nwidth 100000\n").find("cells (limit 2^26)"),
            std::string::npos);
  EXPECT_NE(errorOf([&] {
              loadMovingAiMap(write("u.map", "type octile\nheight 9000\nwidth 9000\nmap\n"), 0.1,
                              64);
            }).find("cells (limit 2^26)"),
            std::string::npos);
  // SBPL .cfg sizes.
  auto cfg = [&](const std::string& size) {
    return errorOf([&] {
      loadSbplEnvironment(write("e.cfg", "discretization(cells): " + size + "\nobsthresh: 254\n"));
    });
  };
  EXPECT_NE(cfg("2000000000 3").find("exceeds 2^26 cells"), std::string::npos);
  EXPECT_NE(cfg("-5 5").find("map size -5 x 5 is not positive"), std::string::npos);
  EXPECT_NE(cfg("99999999999999999999999 5").find("is not positive or exceeds 2^26 cells"),
            std::string::npos);
  EXPECT_NE(cfg("65536 65536").find("exceeds 2^26 cells"), std::string::npos);
  // .mprim counts.
  auto mprim = [&](const std::string& text) {
    std::istringstream in(text);
    return errorOf([&] { readMprim(in, "x.mprim"); });
  };
  EXPECT_NE(mprim("resolution_m: 0.1\nnumberofangles: 100000\n")
                .find("numberofangles 100000 is not in 1..1024"),
            std::string::npos);
  EXPECT_NE(mprim("resolution_m: 0.1\nnumberofangles: -16\n")
                .find("numberofangles -16 is not in 1..1024"),
            std::string::npos);
  EXPECT_NE(mprim("resolution_m: 0.1\nnumberofangles: 1\ntotalnumberofprimitives: 2000000000\n")
                .find("totalnumberofprimitives 2000000000 is not in 1..1000000"),
            std::string::npos);
  EXPECT_NE(mprim("resolution_m: 0.1\nnumberofangles: 1\ntotalnumberofprimitives: 1\nprimID: "
                  "0\nstartangle_c: 0\n"
                  "endpose_c: 1 0 0\nadditionalactioncostmult: 1\nintermediateposes: -1\n")
                .find("intermediateposes -1 is not in 1..100000"),
            std::string::npos);
  // map_server: a resolution that is not positive.
  write("i.pgm", std::string("P5\n2 2\n255\n") + std::string(4, '\xff'));
  EXPECT_NE(
      errorOf([&] {
        loadMapServerMap(write("y.yaml",
                               "image: i.pgm\nresolution: -0.05\norigin: [0, 0, 0]\nnegate: 0\n"
                               "occupied_thresh: 0.65\nfree_thresh: 0.196\n"));
      }).find("resolution -0.05 is not positive"),
      std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// Absurd robots and the planner's setup (issue 22, item 2): refused up front, or stopped by the
// request's cancel, time budget and memory cap.

std::string setupError(const std::shared_ptr<GridMap>& map, const LatticeConfig& c,
                       LatticeError::Kind* kind) {
  try {
    LatticePlanner p(map, c);
  } catch (const LatticeError& e) {
    *kind = e.kind();
    return e.what();
  }
  return "";
}

// A robot wider than the map fits nowhere; one whose sweeps would touch millions of cells took
// minutes and gigabytes (a 100 m robot on the 56 x 61 m Willow Garage map: killed after 240 s at
// 5.4 GB). Both are refused before any sweep is rasterised.
TEST(LatticeLimits, RobotsWiderThanTheMapOrSweepingMillionsOfCellsAreRefusedAtOnce) {
  auto map = test::randomMap(400, 300, 0.1, 1, 0, 0);  // 40 x 30 m
  LatticeError::Kind kind = LatticeError::Kind::kMap;
  LatticeConfig c;
  for (double r : {15.01, 30.0, 100.0, 1e6}) {
    c.robot.radius = r;
    const auto t0 = Clock::now();
    const std::string why = setupError(map, c, &kind);
    EXPECT_LT(secondsSince(t0), 0.5) << r;
    EXPECT_EQ(kind, LatticeError::Kind::kRobot) << r;
    EXPECT_NE(why.find("is wider than the map (40 x 30 m)"), std::string::npos) << why;
  }
  c.robot.radius = 14.0;  // a disc that fits, but sweeps of ~6 x 10^6 cells
  const auto t0 = Clock::now();
  const std::string why = setupError(map, c, &kind);
  EXPECT_LT(secondsSince(t0), 0.5);
  EXPECT_EQ(kind, LatticeError::Kind::kRobot);
  EXPECT_NE(why.find("would touch up to"), std::string::npos) << why;
  // A big robot within both limits is still built.
  c.robot.radius = 1.5;
  EXPECT_EQ(setupError(map, c, &kind), "");
}

// Turning radii far below a cell ended in an OpenCV assertion (an arc of zero radius); coarse
// blocks of 10^5 cells hung (k^2 work per action). Both are configuration errors now.
TEST(LatticeLimits, TinyTurningRadiiAndHugeCoarseBlocksAreRefused) {
  auto map = test::randomMap(100, 100, 0.1, 1, 0, 0);
  LatticeError::Kind kind = LatticeError::Kind::kMap;
  LatticeConfig c;
  const double inf = std::numeric_limits<double>::infinity();
  for (double r : {1e-9, 0.0, -0.5, std::nan(""), -inf, inf, 0.0009}) {
    c.motion.turning_radius = r;
    const std::string why = setupError(map, c, &kind);
    EXPECT_EQ(kind, LatticeError::Kind::kConfig) << r;
    EXPECT_NE(why.find("below a hundredth of a cell (0.001 m"), std::string::npos) << why;
  }
  c.motion.turning_radius = 0.001;  // a hundredth of a cell: the tightest arcs
  EXPECT_EQ(setupError(map, c, &kind), "");
  c = LatticeConfig();
  for (int k : {-1, kMaxCoarseBlock + 1, 100000, INT_MAX}) {
    c.heuristics.coarse_block = k;
    const auto t0 = Clock::now();
    const std::string why = setupError(map, c, &kind);
    EXPECT_LT(secondsSince(t0), 0.5);
    EXPECT_EQ(kind, LatticeError::Kind::kConfig) << k;
    EXPECT_NE(why.find("coarse_block"), std::string::npos) << why;
  }
}

// The per-map work honours the request's limits: a cancel or the time budget stops the
// footprint sweeps of a large robot (seconds of work) within milliseconds, and a memory cap
// below the estimated per-map data refuses it before it starts.
TEST(LatticeLimits, SetupHonoursCancelTimeBudgetAndMemoryCap) {
  auto map = test::randomMap(600, 600, 0.1, 1, 0, 0);
  LatticeConfig c;
  c.robot.radius = 8.0;  // ~3.5 M swept cells with the default primitives: seconds to rasterise
  auto stopped = [&](const SearchLimits& limits, double* took) {
    const auto t0 = Clock::now();
    try {
      LatticePlanner p(map, c, limits);
    } catch (const SetupStopped& e) {
      *took = secondsSince(t0);
      return e.status();
    }
    *took = secondsSince(t0);
    return SearchStatus::kNoSolution;  // not stopped
  };
  double took = 0.0;
  SearchLimits budget;
  budget.time_limit_s = 0.05;
  EXPECT_EQ(stopped(budget, &took), SearchStatus::kTimeLimit);
  EXPECT_LT(took, 0.05 + kLatencyBound);

  std::atomic<bool> cancel{false};
  SearchLimits cancellable;
  cancellable.cancel = &cancel;
  SearchStatus status = SearchStatus::kNoSolution;
  std::thread t([&] { status = stopped(cancellable, &took); });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const auto t_cancel = Clock::now();
  cancel = true;
  t.join();
  EXPECT_EQ(status, SearchStatus::kCancelled);
  EXPECT_LT(secondsSince(t_cancel), kLatencyBound);

  SearchLimits capped;
  capped.max_memory_bytes = 32u << 20;  // the sweeps alone need ~55 MB
  EXPECT_EQ(stopped(capped, &took), SearchStatus::kMemoryLimit);
  EXPECT_LT(took, kRefusalBound);
  try {
    LatticePlanner p(map, c, capped);
  } catch (const SetupStopped& e) {
    EXPECT_NE(std::string(e.what()).find("above the memory cap of 33 MB"), std::string::npos)
        << e.what();
  }

  // A plan's heuristic grids count against its memory cap too (4 grids of 4 bytes a cell).
  c.robot.radius = 0.2;
  LatticePlanner planner(map, c);
  SearchLimits small;
  small.max_memory_bytes = 600 * 600;
  const PlanResult r = planner.plan({10.0, 10.0, 0.0}, {50.0, 50.0, 0.0},
                                    defaultConfig(Algorithm::kAmhaStar), small);
  EXPECT_EQ(r.error, QueryError::kNone) << r.message;
  EXPECT_EQ(r.search.status, SearchStatus::kMemoryLimit);
  EXPECT_TRUE(r.solutions.empty());
}

// ---------------------------------------------------------------------------------------------
// Cancels and deadlines during the heuristic grids, and concurrent plan() calls.

// The grids of a new goal on a 2000 x 2000 map take ~1 s: a cancel or the time budget must
// stop them within milliseconds, and must not leave a broken cache entry behind.
TEST(LatticeLimits, CancelOrDeadlineDuringTheHeuristicGrids) {
  auto map = bigMap(2000, 2);
  LatticePlanner planner(map, LatticeConfig());
  const double c = 1000 * 0.05;
  const Pose2D start{c, c, 0.0}, goal{c + 2.0, c - 1.0, 0.0};
  const PlannerConfig amha = defaultConfig(Algorithm::kAmhaStar);

  std::atomic<bool> cancel{false};
  SearchLimits limits;
  limits.cancel = &cancel;
  PlanResult r;
  std::thread t([&] { r = planner.plan(start, goal, amha, limits); });
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const auto t_cancel = Clock::now();
  cancel = true;
  t.join();
  const double latency = secondsSince(t_cancel);
  EXPECT_EQ(r.search.status, SearchStatus::kCancelled);
  EXPECT_TRUE(r.solutions.empty());
  EXPECT_GT(r.heuristic_seconds, 0.0);
  EXPECT_LT(latency, kLatencyBound);

  SearchLimits budget;
  budget.time_limit_s = 0.03;
  const auto t0 = Clock::now();
  r = planner.plan(start, goal, amha, budget);
  const double took = secondsSince(t0);
  EXPECT_EQ(r.search.status, SearchStatus::kTimeLimit);
  EXPECT_TRUE(r.solutions.empty());
  EXPECT_LT(took, 0.03 + kLatencyBound);
  std::cout << "[ limits   ] 2000 x 2000: cancel during the grids answered in " << latency * 1000
            << " ms; a 30 ms budget returned after " << took * 1000 << " ms" << std::endl;

  // Without limits the same goal plans (the stopped computations were not cached).
  r = planner.plan(start, goal, amha, SearchLimits());
  ASSERT_FALSE(r.solutions.empty()) << statusName(r.search.status);
  EXPECT_GT(r.heuristic_seconds, 0.0);
  EXPECT_TRUE(posesCollisionFree(planner, r.solutions.back().poses));
}

// Two calls need the same new grids; the one that is cancelled returns at once, the other still
// gets them (computing them itself if the cancelled call was the one computing).
TEST(LatticeLimits, ConcurrentCallsForTheSameGridsOneCancelled) {
  auto map = bigMap(2000, 3);
  LatticePlanner planner(map, LatticeConfig());
  const double c = 1000 * 0.05;
  const Pose2D start{c, c, 0.0}, goal{c - 1.0, c + 2.0, M_PI};
  const PlannerConfig amha = defaultConfig(Algorithm::kAmhaStar);
  for (int order = 0; order < 2; ++order) {
    std::atomic<bool> cancel{false};
    SearchLimits cancellable;
    cancellable.cancel = &cancel;
    PlanResult a, b;
    std::thread first, second;
    // order 0: the cancelled call starts first (and computes); order 1: it waits for the other.
    const Pose2D g{goal.x + order * 0.5, goal.y, goal.theta};
    auto run_cancelled = [&] { a = planner.plan(start, g, amha, cancellable); };
    auto run_plain = [&] { b = planner.plan(start, g, amha, SearchLimits()); };
    first = order == 0 ? std::thread(run_cancelled) : std::thread(run_plain);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    second = order == 0 ? std::thread(run_plain) : std::thread(run_cancelled);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const auto t_cancel = Clock::now();
    cancel = true;
    (order == 0 ? first : second).join();
    const double latency = secondsSince(t_cancel);
    (order == 0 ? second : first).join();
    EXPECT_EQ(a.search.status, SearchStatus::kCancelled) << "order " << order;
    EXPECT_LT(latency, kLatencyBound) << "order " << order;
    std::cout << "[ limits   ] order " << order << ": the cancelled call returned "
              << latency * 1000 << " ms after its cancel" << std::endl;
    ASSERT_FALSE(b.solutions.empty()) << "order " << order << ": " << statusName(b.search.status);
    EXPECT_TRUE(posesCollisionFree(planner, b.solutions.back().poses));
  }
}

// One planner, plan() from several threads at once with random cancels: every uncancelled call
// gives exactly the solutions a call alone gives, every cancelled one a prefix of them, and
// every path runs from the start to the goal without collision.
TEST(LatticeConcurrent, PlanFromSeveralThreadsWithCancels) {
  auto map = test::randomMap(70, 70, 0.05, 5, 20, 120);
  LatticeConfig config;
  config.motion.turning_radius = 0.2;
  config.robot.footprint = test::rectangle(0.09, 0.06);
  config.cache.size = 2;  // fewer slots than goals: entries are evicted while in use
  LatticePlanner planner(map, config);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coord(0.1, 3.4), angle(-M_PI, M_PI);
  struct Query {
    Pose2D start, goal;
    PlannerConfig algorithm;
    PlanResult alone;
  };
  std::vector<Query> queries;
  const Algorithm algorithms[] = {Algorithm::kAmhaStar, Algorithm::kAraStar, Algorithm::kAnaStar,
                                  Algorithm::kAStar};
  while (queries.size() < 8) {
    Query q{{coord(rng), coord(rng), angle(rng)},
            {coord(rng), coord(rng), angle(rng)},
            defaultConfig(algorithms[queries.size() % 4]),
            {}};
    if (planner.checkQuery(q.start, q.goal, nullptr) != QueryError::kNone) continue;
    q.alone = planner.plan(q.start, q.goal, q.algorithm, SearchLimits());
    queries.push_back(q);
  }
  constexpr int kThreads = 4, kCalls = 12;
  std::atomic<int> cancelled_calls{0}, checked{0};
  std::vector<std::string> failures(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      std::mt19937 r(100 + t);
      for (int k = 0; k < kCalls; ++k) {
        const Query& q = queries[r() % queries.size()];
        std::atomic<bool> cancel{false};
        SearchLimits limits;
        const bool cancelling = r() % 2 == 0;
        std::thread canceller;
        if (cancelling) {
          limits.cancel = &cancel;
          const int delay_us = static_cast<int>(r() % 3000);
          canceller = std::thread([&cancel, delay_us] {
            std::this_thread::sleep_for(std::chrono::microseconds(delay_us));
            cancel = true;
          });
        }
        const PlanResult got = planner.plan(q.start, q.goal, q.algorithm, limits);
        if (canceller.joinable()) canceller.join();
        std::ostringstream why;
        if (got.solutions.size() > q.alone.solutions.size()) why << "more solutions than alone; ";
        for (std::size_t i = 0; i < std::min(got.solutions.size(), q.alone.solutions.size()); ++i) {
          if (got.solutions[i].search.cost != q.alone.solutions[i].search.cost)
            why << "solution " << i << " cost differs; ";
        }
        if (got.search.status == SearchStatus::kCancelled) {
          ++cancelled_calls;
          if (!cancelling) why << "cancelled without a cancel; ";
        } else if (got.search.status != q.alone.search.status ||
                   got.solutions.size() != q.alone.solutions.size()) {
          why << "status " << statusName(got.search.status) << " / " << got.solutions.size()
              << " solutions, alone " << statusName(q.alone.search.status) << " / "
              << q.alone.solutions.size() << "; ";
        }
        for (const LatticeSolution& s : got.solutions) {
          if (std::hypot(s.poses.front().x - q.start.x, s.poses.front().y - q.start.y) > 0.05 ||
              std::hypot(s.poses.back().x - q.goal.x, s.poses.back().y - q.goal.y) > 0.05) {
            why << "path does not join the start and the goal; ";
          }
          if (!posesCollisionFree(planner, s.poses)) why << "path collides; ";
        }
        if (!why.str().empty())
          failures[t] += "call " + std::to_string(k) + ": " + why.str() + "\n";
        ++checked;
      }
    });
  }
  for (auto& t : threads) t.join();
  for (const std::string& f : failures) EXPECT_EQ(f, "");
  EXPECT_EQ(checked.load(), kThreads * kCalls);
  std::cout << "[ limits   ] " << checked.load() << " concurrent calls, " << cancelled_calls.load()
            << " cancelled" << std::endl;
}

}  // namespace
}  // namespace lattice
}  // namespace amha
