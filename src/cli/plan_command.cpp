// `amha plan`: plan on a map with the lattice planner, printing every improved solution.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>

#include <CLI/CLI.hpp>

#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/lattice/path_smoother.h"
#include "command_registry.h"
#include "exit_codes.h"
#include "keep_freed_memory.h"
#include "lattice_image.h"
#include "lattice_options.h"
#include "path_metrics.h"
#include "run_json.h"
#include "schedule_option.h"
#include "weight_options.h"

namespace amha {
namespace cli {

namespace {

int planMain(int argc, char** argv) {
  // One plan per process: what is freed goes back to the kernel at once (keep_freed_memory.h).
  unmapFreedLargeBlocks();
  CLI::App app(
      "Plans a path for a robot with (x, y, heading) states on a map, anytime: every improved "
      "solution is printed as it is found.",
      argv[0]);
  LatticeOptions lo;
  lo.addTo(app);
  std::string start_text, goal_text, algorithm_name = "amha", json_path, image_path;
  double time_limit = 10.0, goal_tolerance = 0.0;
  std::optional<double> w1, w2, dw1, dw2, eps;
  QueueSchedule schedule = QueueSchedule::kRoundRobin;
  app.add_option("--start", start_text,
                 "start pose x,y,theta (m, m, rad; .cfg maps: the file's start)");
  app.add_option("--goal", goal_text, "goal pose x,y,theta (.cfg maps: the file's end)");
  app.add_option(
      "--goal-tolerance", goal_tolerance,
      "metres: if the goal is in collision, plan to the nearest collision-free pose within this "
      "distance that the start can reach (default 0: the exact goal)");
  double start_tolerance = 0.0, escape_penalty = lattice::StartOptions().penalty;
  app.add_option(
      "--start-tolerance", start_tolerance,
      "metres: if the start is in collision, the path may first leave it by motions across "
      "inscribed "
      "cells and the obstacle cells under the robot, within this distance (default 0: refuse it)");
  app.add_option("--escape-penalty", escape_penalty,
                 "with --start-tolerance: an escape motion costs this times its cost across the "
                 "costliest free "
                 "cells (default 2, >= 1)");
  bool complete_grids = false;
  app.add_flag("--complete-grids", complete_grids,
               "complete the heuristic grids over the whole map (the server's default); without "
               "it they stop past the best path's cost once the search has one, which saves memory "
               "and the second core's time but leaves later iterations' expansions (not the "
               "costs) to the timing of the two threads");
  bool any_goal_heading = false;
  app.add_flag(
      "--any-goal-heading", any_goal_heading,
      "end at the goal's position with whichever heading is cheapest (its own is ignored)");
  app.add_option("--algorithm", algorithm_name,
                 "amha | mha | ara | ana | wastar | astar (default amha)");
  app.add_option("--time-limit", time_limit,
                 "seconds, heuristic computation included (default 10)");
  app.add_option("--w1", w1, "initial w1 (anchor inflation; epsilon for ara/wastar), in [1, 1e6]")
      ->check(weightRange());
  app.add_option("--w2", w2, "initial w2 (amha/mha), in [1, 1e6]")->check(weightRange());
  app.add_option("--dw1", dw1, "decrement of w1 per iteration, in [0, 1e6]")
      ->check(decrementRange());
  app.add_option("--dw2", dw2, "decrement of w2 per iteration, in [0, 1e6]")
      ->check(decrementRange());
  cli::addScheduleOption(app, &schedule);
  std::optional<std::string> weights_name;
  std::optional<double> certified_ratio, certified_split, final_gap;
  app.add_option(
      "--weights", weights_name,
      "anytime weight schedule of amha/ara: certified (from the last certified bound) or decrement "
      "(the paper's: w -= dw)");
  app.add_option("--certified-ratio", certified_ratio,
                 "certified schedule: next bound = 1 + ratio x (c - 1)");
  app.add_option("--certified-split", certified_split,
                 "certified schedule: w1 = bound^split, w2 = bound / w1");
  app.add_option("--final-gap", final_gap,
                 "certified schedule: prove optimality once c <= 1 + gap");
  std::optional<double> stall_expansions, stall_w1;
  app.add_option(
      "--stall-expansions", stall_expansions,
      "amha/ara: after this many expansions without a path, go on with w1 = --stall-w1 (0: never)");
  app.add_option("--stall-w1", stall_w1,
                 "amha/ara: the w1 a stalled first iteration goes on with, in [1, 1e6]")
      ->check(weightRange());
  std::optional<double> stall_mid_expansions, stall_mid_w1;
  app.add_option("--stall-mid-w1", stall_mid_w1,
                 "amha/ara: a rung before --stall-w1: a stalled first iteration goes on with this "
                 "w1 first (if between the two), in [1, 1e6]")
      ->check(weightRange());
  app.add_option("--stall-mid-expansions", stall_mid_expansions,
                 "amha/ara: ... for this many more expansions, then --stall-w1 (0: no such rung)");
  // Switches whose default is the preset's: a CLI11 flag bound to std::optional<bool> holds
  // false when absent, so each is a bool read only if given (--x or --x=false).
  bool publish_within = false, proof_anchor_only = false;
  CLI::Option* publish_within_opt = app.add_flag(
      "--publish-within", publish_within,
      "publish cheaper paths as soon as an iteration finds them (the default for amha; "
      "--publish-within=false: only at the end of each iteration)");
  CLI::Option* proof_anchor_only_opt =
      app.add_flag("--proof-anchor-only", proof_anchor_only,
                   "amha: prove (w1 = w2 = 1) with the anchor alone, as A* (the default; "
                   "--proof-anchor-only=false: every queue, as the paper's Algorithm 1)");
  app.add_option("--eps", eps, "initial epsilon for ara/wastar (same as --w1), in [1, 1e6]")
      ->check(weightRange());
  app.add_option("--json", json_path,
                 "write the run (runs/solutions schema + the final path) to this file");
  app.add_option("--image", image_path,
                 "write a PNG of the map, the improved paths and the footprint");
  bool smooth = false;
  app.add_flag("--smooth", smooth,
               "smooth every solution (Dubins shortcuts that keep the lattice's collision test, "
               "turning radius and "
               "cost bound); the smoothed path is the result, --json keeps the lattice path too");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitUsage;
  }

  Algorithm algorithm;
  if (!parseAlgorithm(algorithm_name, &algorithm)) {
    std::cerr << "amha plan: unknown algorithm '" << algorithm_name
              << "' (amha, mha, ara, ana, wastar, astar)\n";
    return kExitUsage;
  }
  PlannerConfig pc = lattice::defaultPlannerConfig(algorithm);
  if (eps && w1) {
    std::cerr << "amha plan: give --eps or --w1, not both\n";
    return kExitUsage;
  }
  applyWeights({eps ? eps : w1, w2, dw1, dw2}, &pc);
  pc.schedule = schedule;
  if (weights_name && !parseWeightSchedule(*weights_name, &pc.weight_schedule)) {
    std::cerr << "amha plan: --weights must be certified or decrement, not '" << *weights_name
              << "'\n";
    return kExitUsage;
  }
  pc.certified_ratio = certified_ratio.value_or(pc.certified_ratio);
  pc.certified_split = certified_split.value_or(pc.certified_split);
  pc.final_gap = final_gap.value_or(pc.final_gap);
  if (publish_within_opt->count() > 0) pc.publish_within_iterations = publish_within;
  if (proof_anchor_only_opt->count() > 0) pc.proof_anchor_only = proof_anchor_only;
  // An expansion count given as a number (so that 1e4 reads): false, with a message, if it is
  // not one in [0, 1e15].
  auto expansions = [](const char* option, const std::optional<double>& v, std::uint64_t* out) {
    if (!v) return true;
    if (!(*v >= 0.0 && *v <= 1e15)) {
      std::cerr << "amha plan: " << option << " " << *v
                << ": expected a number of expansions in [0, 1e15]\n";
      return false;
    }
    *out = static_cast<std::uint64_t>(*v);
    return true;
  };
  if (!expansions("--stall-expansions", stall_expansions, &pc.stall_expansions) ||
      !expansions("--stall-mid-expansions", stall_mid_expansions, &pc.stall_mid_expansions))
    return kExitUsage;
  pc.stall_w1 = stall_w1.value_or(pc.stall_w1);
  pc.stall_mid_w1 = stall_mid_w1.value_or(pc.stall_mid_w1);
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
  if (!(start_tolerance >= 0.0) || !std::isfinite(start_tolerance)) {
    std::cerr << "amha plan: --start-tolerance must be finite and >= 0\n";
    return kExitUsage;
  }
  if (!(escape_penalty >= 1.0) || !std::isfinite(escape_penalty)) {
    std::cerr << "amha plan: --escape-penalty must be finite and >= 1\n";
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
  lattice::GoalOptions goal_options;
  goal_options.tolerance = goal_tolerance;
  goal_options.any_heading = any_goal_heading;
  std::unique_ptr<lattice::LatticePlanner> planner;
  double setup_s = 0.0, table_s = 0.0;
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
    // One query: its grids need not reach past its path's cost for a later query to the goal.
    loaded.config.cache.complete_grids = complete_grids;
    const auto t0 = std::chrono::steady_clock::now();
    planner.reset(new lattice::LatticePlanner(loaded.map, loaded.config, limits));
    setup_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // The kinematic tables share the budget that the setup left; the search gets the rest.
    const auto t1 = std::chrono::steady_clock::now();
    SearchLimits table_limits = limits;
    table_limits.time_limit_s = std::max(0.0, time_limit - setup_s);
    // Only this query's table (its goal heading's, searching backward its start's): a process
    // that plans once need not build the others.
    planner->prepareKinematicTables(start, goal, goal_options, table_limits);
    table_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
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
  std::printf(
      "map %s: %d x %d cells of %.3f m; algorithm %s; planner setup (primitives, footprint sweeps, "
      "clearance, openings) %.3f s; kinematic tables %.3f s, %.1f MB\n",
      lo.map_file.c_str(), map.width, map.height, map.resolution, algorithmName(algorithm), setup_s,
      table_s, planner->kinematicTableBytes() / 1e6);
  std::printf("start (%.3f, %.3f, %.3f)  goal (%.3f, %.3f, %.3f)\n", start.x, start.y, start.theta,
              goal.x, goal.y, goal.theta);

  limits.time_limit_s = std::max(0.0, time_limit - setup_s - table_s);
  int count = 0;
  std::unique_ptr<lattice::PathSmoother> smoother;
  std::unique_ptr<lattice::SmoothedStream> stream;
  lattice::LatticeSolution published;  // with --smooth: the smoothed path published last
  if (smooth) {
    smoother.reset(new lattice::PathSmoother(planner->graph()));
    stream.reset(new lattice::SmoothedStream(*smoother));
    std::printf("smoothing: shortcut turning radius %.3f m\n", smoother->turningRadius());
  }
  auto print = [&](const lattice::LatticeSolution& s) {
    const Solution& q = s.search;
    std::printf(
        "solution %d: t=%.4f s  cost=%lld  bound=%.3f  certified=%.3f  expansions=%llu  "
        "poses=%zu\n",
        ++count, s.elapsed_total_s, static_cast<long long>(q.cost), q.nominal_bound,
        q.certified_bound, static_cast<unsigned long long>(q.expansions), s.poses.size());
    if (stream) {
      const lattice::SmoothedStream::Step& step = stream->add(s);
      std::printf("  smoothed: cost=%lld  certified=%.3f  shortcuts=%zu  %.3f ms%s\n",
                  static_cast<long long>(step.published.search.cost),
                  step.published.search.certified_bound, step.smoothed.shortcuts,
                  1e3 * step.smoothed.seconds,
                  step.republished ? "  (an earlier smoothed path is cheaper: kept)" : "");
      published = step.published;
    }
    std::fflush(stdout);
  };
  lattice::StartOptions start_options;
  start_options.tolerance = start_tolerance;
  start_options.penalty = escape_penalty;
  const lattice::PlanResult r =
      planner->plan(start, goal, start_options, goal_options, pc, limits, print);
  if (r.error != lattice::QueryError::kNone) {
    std::cerr << "amha plan: " << r.message << "\n";
    const bool is_start = r.error == lattice::QueryError::kStartNotFinite ||
                          r.error == lattice::QueryError::kStartOutOfMap ||
                          r.error == lattice::QueryError::kStartInCollision;
    if (r.error == lattice::QueryError::kGoalUnreachable) return kExitNoSolution;
    return is_start ? kExitBadStart : kExitBadGoal;
  }
  if (r.start_escaped)
    std::printf("%s\nstart escape %.4f s\n", r.escape_message.c_str(), r.escape_seconds);
  if (r.goal_substituted)
    std::printf("%s\ngoal choice %.4f s\n", r.message.c_str(), r.goal_seconds);
  std::printf(
      "status %s: %zu solutions, %llu expansions, %zu states, %.1f MB, heuristics %.4f s, total "
      "%.4f s\n",
      statusName(r.search.status), r.solutions.size(),
      static_cast<unsigned long long>(r.search.expansions), r.search.peak_states,
      r.search.peak_memory_bytes / 1e6, r.heuristic_seconds, r.totalSeconds());
  if (!r.no_path_reason.empty()) std::printf("no path: %s\n", r.no_path_reason.c_str());

  // The result: the last solution, or with --smooth the smoothed path published last.
  std::vector<lattice::Pose2D> result_path;
  if (!r.solutions.empty()) result_path = stream ? published.poses : r.solutions.back().poses;
  if (stream && !r.solutions.empty()) {
    const PathMetrics a = pathMetrics(r.solutions.back().poses), b = pathMetrics(result_path);
    std::printf(
        "smoothed path: length %.2f m (lattice %.2f m), mean |curvature| %.3f /m (lattice %.3f), "
        "max %.3f /m "
        "(lattice %.3f), |dheading| %.3f rad/m (lattice %.3f), curvature sign changes %d (lattice "
        "%d)\n",
        b.length, a.length, b.mean_curvature, a.mean_curvature, b.max_curvature, a.max_curvature,
        b.heading_change_per_metre, a.heading_change_per_metre, b.curvature_sign_changes,
        a.curvature_sign_changes);
  }
  auto poses_json = [](const std::vector<lattice::Pose2D>& poses) {
    nlohmann::json path = nlohmann::json::array();
    for (const auto& p : poses) path.push_back({p.x, p.y, p.theta});
    return path;
  };
  try {
    if (!json_path.empty()) {
      nlohmann::json run =
          runToJson(lo.map_file, algorithm, r.search, r.searchSolutions(), std::nullopt);
      run["path"] = poses_json(result_path);
      if (stream && !r.solutions.empty()) {
        run["smoothed"] = true;
        run["smoothed_cost"] = published.search.cost;
        run["smoothed_certified_bound"] = published.search.certified_bound;
        run["lattice_path"] = poses_json(r.solutions.back().poses);
      }
      run["heuristic_seconds"] = r.heuristic_seconds;
      if (r.no_path != lattice::NoPathProof::kNone) {
        run["no_path"] = lattice::noPathProofName(r.no_path);
        run["enclosed_states"] = r.enclosed_states;  // counted by the walk; 0 after a search
        run["no_path_reason"] = r.no_path_reason;
      }
      run["search"] = searchConfigToJson(pc);
      nlohmann::json extra = {{"start", {start.x, start.y, start.theta}},
                              {"goal", {goal.x, goal.y, goal.theta}},
                              {"cost_units_per_metre", lattice::kCostUnitsPerMetre}};
      if (r.planned_goal)
        extra["planned_goal"] = {r.planned_goal->x, r.planned_goal->y, r.planned_goal->theta};
      extra["goal_tolerance"] = goal_tolerance;
      extra["goal_substituted"] = r.goal_substituted;
      extra["any_goal_heading"] = any_goal_heading;
      extra["start_tolerance"] = start_tolerance;
      extra["start_escaped"] = r.start_escaped;
      if (!r.solutions.empty()) extra["escape_poses"] = r.solutions.back().escape_poses;
      writeRunsJson(json_path, nlohmann::json::array({run}), extra);
    }
    if (!image_path.empty()) {
      std::vector<std::vector<lattice::Pose2D>> paths;
      for (const auto& s : r.solutions) paths.push_back(s.poses);
      if (stream && !r.solutions.empty())
        paths.push_back(result_path);  // drawn last, with the footprint
      writePlanImage(
          image_path, map, paths, [&](const lattice::Pose2D& p) { return planner->footprintAt(p); },
          start, goal);
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
