// `amha plan`: plan on a map with the lattice planner, printing every improved solution.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <cstdio>
#include <iostream>

#include <CLI/CLI.hpp>

#include "amha_planner/lattice/lattice_planner.h"
#include "command_registry.h"
#include "exit_codes.h"
#include "lattice_image.h"
#include "lattice_options.h"
#include "run_json.h"
#include "schedule_option.h"
#include "weight_options.h"

namespace amha {
namespace cli {

namespace {

int planMain(int argc, char** argv) {
  CLI::App app("Plans a path for a robot with (x, y, heading) states on a map, anytime: every improved "
               "solution is printed as it is found.", argv[0]);
  LatticeOptions lo;
  lo.addTo(app);
  std::string start_text, goal_text, algorithm_name = "amha", json_path, image_path;
  double time_limit = 10.0, goal_tolerance = 0.0;
  std::optional<double> w1, w2, dw1, dw2, eps;
  QueueSchedule schedule = QueueSchedule::kRoundRobin;
  app.add_option("--start", start_text, "start pose x,y,theta (m, m, rad; .cfg maps: the file's start)");
  app.add_option("--goal", goal_text, "goal pose x,y,theta (.cfg maps: the file's end)");
  app.add_option("--goal-tolerance", goal_tolerance,
                 "metres: if the goal is in collision, plan to the nearest collision-free pose within this "
                 "distance that the start can reach (default 0: the exact goal)");
  bool any_goal_heading = false;
  app.add_flag("--any-goal-heading", any_goal_heading,
               "end at the goal's position with whichever heading is cheapest (its own is ignored)");
  app.add_option("--algorithm", algorithm_name, "amha | mha | ara | ana | wastar | astar (default amha)");
  app.add_option("--time-limit", time_limit, "seconds, heuristic computation included (default 10)");
  app.add_option("--w1", w1, "initial w1 (anchor inflation; epsilon for ara/wastar), in [1, 1e6]")->check(weightRange());
  app.add_option("--w2", w2, "initial w2 (amha/mha), in [1, 1e6]")->check(weightRange());
  app.add_option("--dw1", dw1, "decrement of w1 per iteration, in [0, 1e6]")->check(decrementRange());
  app.add_option("--dw2", dw2, "decrement of w2 per iteration, in [0, 1e6]")->check(decrementRange());
  cli::addScheduleOption(app, &schedule);
  app.add_option("--eps", eps, "initial epsilon for ara/wastar (same as --w1), in [1, 1e6]")->check(weightRange());
  app.add_option("--json", json_path, "write the run (runs/solutions schema + the final path) to this file");
  app.add_option("--image", image_path, "write a PNG of the map, the improved paths and the footprint");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitUsage;
  }

  Algorithm algorithm;
  if (!parseAlgorithm(algorithm_name, &algorithm)) {
    std::cerr << "amha plan: unknown algorithm '" << algorithm_name << "' (amha, mha, ara, ana, wastar, astar)\n";
    return kExitUsage;
  }
  PlannerConfig pc = defaultConfig(algorithm);
  if (eps && w1) {
    std::cerr << "amha plan: give --eps or --w1, not both\n";
    return kExitUsage;
  }
  pc.w1 = eps.value_or(w1.value_or(pc.w1));
  pc.w2 = w2.value_or(pc.w2);
  pc.dw1 = dw1.value_or(pc.dw1);
  pc.dw2 = dw2.value_or(pc.dw2);
  pc.schedule = schedule;
  try {
    makePlanner(pc);  // validates the weights before any heavy work
  } catch (const std::invalid_argument& e) {
    std::cerr << "amha plan: " << e.what() << "\n";
    return kExitUsage;
  }
  if (!(goal_tolerance >= 0.0) || !std::isfinite(goal_tolerance)) {
    std::cerr << "amha plan: --goal-tolerance must be finite and >= 0\n";
    return kExitUsage;
  }
  if (!(time_limit > 0.0)) {
    std::cerr << "amha plan: --time-limit must be positive\n";
    return kExitUsage;
  }
  // The budget covers everything: the planner's setup, the heuristic grids and the search.
  SearchLimits limits;
  limits.time_limit_s = time_limit;

  LoadedLattice loaded;
  lattice::Pose2D start, goal;
  std::unique_ptr<lattice::LatticePlanner> planner;
  double setup_s = 0.0;
  try {
    loaded = loadLattice(lo);
    if (start_text.empty() || goal_text.empty()) {
      if (!loaded.is_sbpl_env) {
        std::cerr << "amha plan: --start and --goal are required (only .cfg maps have their own)\n";
        return kExitUsage;
      }
    }
    start = start_text.empty() ? loaded.env.start : parsePose(start_text, "--start");
    goal = goal_text.empty() ? loaded.env.goal : parsePose(goal_text, "--goal");
    const auto t0 = std::chrono::steady_clock::now();
    planner.reset(new lattice::LatticePlanner(loaded.map, loaded.config, limits));
    setup_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  } catch (const lattice::SetupStopped& e) {
    std::printf("status %s: 0 solutions (%s)\n", statusName(e.status()), e.what());
    return kExitNoSolution;
  } catch (const lattice::LatticeError& e) {
    std::cerr << "amha plan: " << e.what() << "\n";
    return exitCodeFor(e);
  } catch (const std::invalid_argument& e) {
    std::cerr << "amha plan: " << e.what() << "\n";
    return kExitUsage;
  }
  const lattice::GridMap& map = *loaded.map;
  std::printf("map %s: %d x %d cells of %.3f m; algorithm %s; planner setup (primitives, footprint sweeps, "
              "clearance, openings) %.3f s\n", lo.map_file.c_str(), map.width, map.height, map.resolution,
              algorithmName(algorithm), setup_s);
  std::printf("start (%.3f, %.3f, %.3f)  goal (%.3f, %.3f, %.3f)\n", start.x, start.y, start.theta, goal.x, goal.y,
              goal.theta);

  limits.time_limit_s = std::max(0.0, time_limit - setup_s);
  int count = 0;
  auto print = [&count](const lattice::LatticeSolution& s) {
    const Solution& q = s.search;
    std::printf("solution %d: t=%.4f s  cost=%lld  bound=%.3f  certified=%.3f  expansions=%llu  poses=%zu\n",
                ++count, s.elapsed_total_s, static_cast<long long>(q.cost), q.nominal_bound,
                q.certified_bound, static_cast<unsigned long long>(q.expansions), s.poses.size());
    std::fflush(stdout);
  };
  lattice::GoalOptions goal_options;
  goal_options.tolerance = goal_tolerance;
  goal_options.any_heading = any_goal_heading;
  const lattice::PlanResult r = planner->plan(start, goal, goal_options, pc, limits, print);
  if (r.error != lattice::QueryError::kNone) {
    std::cerr << "amha plan: " << r.message << "\n";
    const bool is_start = r.error == lattice::QueryError::kStartNotFinite || r.error == lattice::QueryError::kStartOutOfMap ||
                          r.error == lattice::QueryError::kStartInCollision;
    if (r.error == lattice::QueryError::kGoalUnreachable) return kExitNoSolution;
    return is_start ? kExitBadStart : kExitBadGoal;
  }
  if (r.goal_substituted) std::printf("%s\ngoal choice %.4f s\n", r.message.c_str(), r.goal_seconds);
  std::printf("status %s: %zu solutions, %llu expansions, %zu states, %.1f MB, heuristics %.4f s, total %.4f s\n",
              statusName(r.search.status), r.solutions.size(), static_cast<unsigned long long>(r.search.expansions),
              r.search.peak_states, r.search.peak_memory_bytes / 1e6, r.heuristic_seconds,
              r.goal_seconds + r.heuristic_seconds + r.search.elapsed_s);

  try {
    if (!json_path.empty()) {
      nlohmann::json run = runToJson(lo.map_file, algorithm, r.search, std::nullopt);
      nlohmann::json path = nlohmann::json::array();
      if (!r.solutions.empty()) {
        for (const auto& p : r.solutions.back().poses) path.push_back({p.x, p.y, p.theta});
      }
      run["path"] = path;
      run["heuristic_seconds"] = r.heuristic_seconds;
      nlohmann::json extra = {{"start", {start.x, start.y, start.theta}}, {"goal", {goal.x, goal.y, goal.theta}},
                              {"cost_units_per_metre", lattice::kCostUnitsPerMetre}};
      if (r.planned_goal) extra["planned_goal"] = {r.planned_goal->x, r.planned_goal->y, r.planned_goal->theta};
      extra["goal_tolerance"] = goal_tolerance;
      extra["goal_substituted"] = r.goal_substituted;
      extra["any_goal_heading"] = any_goal_heading;
      writeRunsJson(json_path, nlohmann::json::array({run}), extra);
    }
    if (!image_path.empty()) {
      std::vector<std::vector<lattice::Pose2D>> paths;
      for (const auto& s : r.solutions) paths.push_back(s.poses);
      writePlanImage(image_path, map, paths, [&](const lattice::Pose2D& p) { return planner->footprintAt(p); }, start, goal);
    }
  } catch (const std::exception& e) {
    std::cerr << "amha plan: " << e.what() << "\n";
    return kExitOutput;
  }
  return r.solutions.empty() ? kExitNoSolution : kExitOk;
}

}  // namespace

AMHA_REGISTER_COMMAND("plan", "plan a path on a map (lattice planner)", planMain);

}  // namespace cli
}  // namespace amha
