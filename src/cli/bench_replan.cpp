// `amha bench replan`: what a map update costs the next plan to the same goal. A costmap that
// changes while the robot drives to one goal is the usual case: after each update the planner
// is rebuilt incrementally and asked for the same goal again. Two chains of planners see the
// same updates: one repairs the previous planner's heuristic grids (the default), the other
// computes them again (repair_heuristics off). Both must find the same first solution.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "amha_planner/lattice/lattice_planner.h"
#include "bench_command.h"
#include "exit_codes.h"
#include "lattice_options.h"

namespace amha {
namespace cli {

namespace {

using lattice::CellRect;
using lattice::GridMap;
using lattice::LatticePlanner;

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

struct Replan {
  double build_s = 0, heuristic_s = 0, first_s = 0;  // first_s: first solution, heuristics included
  lattice::HeuristicSource source = lattice::HeuristicSource::kCached;
  bool solved = false;
  Cost first_cost = 0;
};

// Plans until the first solution (then cancels), timing the heuristics and that solution.
Replan planOnce(LatticePlanner& planner, const lattice::Pose2D& start, const lattice::Pose2D& goal,
                Algorithm algorithm, double time_limit) {
  std::atomic<bool> cancel{false};
  SearchLimits limits;
  limits.time_limit_s = time_limit;
  limits.cancel = &cancel;
  Replan r;
  const auto on_solution = [&](const lattice::LatticeSolution& s) {
    if (!r.solved) {
      r.solved = true;
      r.first_s = s.elapsed_total_s;
      r.first_cost = s.search.cost;
    }
    cancel = true;
  };
  const lattice::PlanResult result =
      planner.plan(start, goal, lattice::defaultPlannerConfig(algorithm), limits, on_solution);
  if (result.error != lattice::QueryError::kNone) throw std::invalid_argument(result.message);
  r.heuristic_s = result.heuristic_seconds;
  r.source = result.heuristic_source;
  return r;
}

// A window of the map changed: "same" writes the cells' own values back (a costmap that
// republishes an unchanged area), "obstacle" puts a lethal block in the middle of the window.
CellRect randomUpdate(std::mt19937& rng, const GridMap& map, GridMap& next, int window,
                      bool obstacle, const std::vector<std::array<int, 2>>& keep_clear,
                      int clear_radius) {
  std::uniform_int_distribution<int> px(0, std::max(0, map.width - window)),
      py(0, std::max(0, map.height - window));
  for (int tries = 0;; ++tries) {
    const CellRect r{px(rng), py(rng), 0, 0};
    const CellRect w{r.x0, r.y0, std::min(map.width, r.x0 + window),
                     std::min(map.height, r.y0 + window)};
    bool near = false;
    for (const auto& c : keep_clear) {
      near = near || (c[0] >= w.x0 - clear_radius && c[0] < w.x1 + clear_radius &&
                      c[1] >= w.y0 - clear_radius && c[1] < w.y1 + clear_radius);
    }
    if (near && tries < 1000) continue;
    if (obstacle) {
      const int b = std::max(1, window / 5);
      const int x0 = (w.x0 + w.x1 - b) / 2, y0 = (w.y0 + w.y1 - b) / 2;
      for (int y = std::max(0, y0); y < std::min(map.height, y0 + b); ++y) {
        for (int x = std::max(0, x0); x < std::min(map.width, x0 + b); ++x) {
          next.cost[static_cast<std::size_t>(y) * map.width + x] = lattice::kLethalCost;
        }
      }
    }
    return w;
  }
}

int benchReplanMain(int argc, char** argv) {
  CLI::App app(
      "Plans to one goal after each of a series of map updates, with the previous planner's "
      "heuristic "
      "grids repaired and computed again, and reports the time each takes.",
      argv[0]);
  LatticeOptions lo;
  lo.addTo(app);
  std::string start_text, goal_text, change = "obstacle", algorithm_text = "amha";
  int updates = 20, window = 100;
  unsigned seed = 1;
  double time_limit = 10.0;
  app.add_option("--start", start_text, "start pose x,y,theta (map frame, m and rad)")->required();
  app.add_option("--goal", goal_text, "goal pose x,y,theta")->required();
  app.add_option("--updates", updates, "map updates (default 20)");
  app.add_option("--window", window, "cells per side of an updated window (default 100)");
  app.add_option("--change", change,
                 "what an update does: obstacle (a lethal block of a fifth of the window, "
                 "default) or same (the cells' own values)");
  app.add_option("--seed", seed, "seed of the windows' places (default 1)");
  app.add_option("--algorithm", algorithm_text, "algorithm (default amha)");
  app.add_option("--time-limit", time_limit,
                 "seconds per plan at most (default 10; each plan stops at its first solution)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitUsage;
  }
  Algorithm algorithm;
  if (!parseAlgorithm(algorithm_text, &algorithm) || updates < 1 || window < 1 ||
      !(time_limit > 0.0) || (change != "obstacle" && change != "same")) {
    std::cerr << "amha bench replan: need a known algorithm, --updates and --window >= 1, a "
                 "positive time limit "
                 "and --change obstacle|same\n";
    return kExitUsage;
  }
  LoadedLattice loaded;
  lattice::Pose2D start, goal;
  std::unique_ptr<LatticePlanner> planners[2];  // [0] repairs, [1] computes again
  try {
    loaded = loadLattice(lo);
    start = parsePose(start_text, "--start");
    goal = parsePose(goal_text, "--goal");
    for (int k = 0; k < 2; ++k) {
      lattice::LatticeConfig c = loaded.config;
      c.cache.repair = k == 0;
      planners[k].reset(new LatticePlanner(loaded.map, c));
    }
  } catch (const lattice::LatticeError& e) {
    std::cerr << "amha bench replan: " << e.what() << "\n";
    return exitCodeFor(e);
  } catch (const std::invalid_argument& e) {
    std::cerr << "amha bench replan: " << e.what() << "\n";
    return kExitUsage;
  }
  const GridMap& m0 = *loaded.map;
  std::printf("%s\nmachine: %s\ncommit: %s\nmap: %d x %d cells (%.1f M)\n",
              benchCommandLine(argc, argv).c_str(), machineDescription().c_str(),
              sourceCommit().c_str(), m0.width, m0.height, m0.width * 1e-6 * m0.height);
  const char* names[2] = {"repair", "compute"};
  std::vector<double> build[2], heur[2], first[2];
  int mismatches = 0, unsolved = 0, not_repaired = 0;
  try {
    for (int k = 0; k < 2; ++k) {
      const Replan r = planOnce(*planners[k], start, goal, algorithm, time_limit);
      std::printf("initial plan (%s chain): heuristics %.4f s (%s), first solution after %.4f s\n",
                  names[k], r.heuristic_s, lattice::heuristicSourceName(r.source), r.first_s);
    }
    std::mt19937 rng(seed);
    auto map = loaded.map;
    const double res = m0.resolution;
    auto cell = [&](const lattice::Pose2D& p) {
      return std::array<int, 2>{static_cast<int>((p.x - m0.origin_x) / res),
                                static_cast<int>((p.y - m0.origin_y) / res)};
    };
    // The robot's own surroundings stay as they are, so that start and goal stay valid.
    const int clear = static_cast<int>(2.0 / res);
    std::printf("%-6s %-8s %9s %9s %9s %-9s %12s\n", "update", "chain", "build s", "heur. s",
                "first s", "grids", "first cost");
    for (int u = 0; u < updates; ++u) {
      auto next = std::make_shared<GridMap>(*map);
      const CellRect r = randomUpdate(rng, *map, *next, window, change == "obstacle",
                                      {cell(start), cell(goal)}, clear);
      Replan results[2];
      for (int j = 0; j < 2; ++j) {
        const int k = (u + j) % 2;  // alternate which chain goes first
        const auto t0 = std::chrono::steady_clock::now();
        planners[k].reset(new LatticePlanner(*planners[k], next, r));
        const double b = secondsSince(t0);
        results[k] = planOnce(*planners[k], start, goal, algorithm, time_limit);
        results[k].build_s = b;
      }
      for (int k = 0; k < 2; ++k) {
        const Replan& x = results[k];
        std::printf("%-6d %-8s %9.4f %9.4f %9.4f %-9s %12lld\n", u + 1, names[k], x.build_s,
                    x.heuristic_s, x.solved ? x.first_s : -1.0,
                    lattice::heuristicSourceName(x.source),
                    x.solved ? static_cast<long long>(x.first_cost) : -1LL);
        build[k].push_back(x.build_s);
        heur[k].push_back(x.heuristic_s);
        if (x.solved) first[k].push_back(x.first_s);
      }
      if (results[0].solved != results[1].solved || results[0].first_cost != results[1].first_cost)
        ++mismatches;
      if (!results[0].solved) ++unsolved;
      if (results[0].source != lattice::HeuristicSource::kRepaired) ++not_repaired;
      map = next;
    }
  } catch (const std::invalid_argument& e) {
    std::cerr << "amha bench replan: " << e.what() << "\n";
    return kExitBadStart;
  }
  std::printf("\nmedians over %d updates (first: over the solved ones):\n", updates);
  for (int k = 0; k < 2; ++k) {
    std::printf("  %-8s build %.4f s, heuristics %.4f s, first solution %.4f s\n", names[k],
                median(build[k]), median(heur[k]), median(first[k]));
  }
  std::printf("heuristics: repair / compute = %.3f; first solution: %.3f\n",
              median(heur[0]) / median(heur[1]), median(first[0]) / median(first[1]));
  std::printf(
      "updates whose grids were not repaired: %d; unsolved: %d; first solutions that differ: %d\n",
      not_repaired, unsolved, mismatches);
  return mismatches == 0 ? kExitOk : kExitInternal;
}

}  // namespace

AMHA_REGISTER_BENCHMARK(
    "replan",
    "a plan to the same goal after each map update: heuristic grids repaired vs computed again",
    benchReplanMain);

}  // namespace cli
}  // namespace amha
