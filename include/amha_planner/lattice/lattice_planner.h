// The lattice domain's public face, used by `amha plan`, the benchmarks and the ROS layer:
// a map, a robot (footprint + motion primitives), and anytime planning between two poses.
// Everything here is ROS-free; poses are in the map frame (REP 103: metres, radians, x forward).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "amha_planner/lattice/lattice_config.h"
#include "amha_planner/lattice/map_types.h"
#include "amha_planner/search/planner.h"

namespace amha {
namespace lattice {

/// What counts as reaching the goal (the defaults: the goal pose exactly, as plan() without
/// options).
struct GoalOptions {
  /// Metres, as nav_msgs/GetPlan's tolerance: a goal inside the map but in collision is replaced
  /// by the nearest collision-free pose within this distance of it that the start may reach
  /// (nearestReachableGoal in goal_tolerance.h; PlanResult::goal_substituted and planned_goal
  /// say so). A collision-free goal is planned to exactly, whatever the tolerance. If there is
  /// no collision-free pose within the tolerance the error is kGoalInCollision, if none of them
  /// is reachable kGoalUnreachable. The time spent choosing counts against the budget.
  double tolerance = 0.0;
  /// Any heading at the goal's cell will do: the search ends at whichever is cheapest to reach
  /// (the goal's own heading is ignored; the goal is in collision only if every heading
  /// collides there). The bounds are relative to the optimal cost to any of them.
  bool any_heading = false;
};

/// What may happen when the start is in collision (the default refuses such a start with
/// kStartInCollision, as plan() without options).
struct StartOptions {
  /// Metres; 0: no escape. A start whose footprint collides (its centre on an inscribed, lethal
  /// or unknown cell, or an obstacle under its footprint, as from a pose drifting into the
  /// inflation or a person standing within the footprint) may leave the collision by motions
  /// that cross inscribed cells and the obstacle cells the robot already stands on, never other
  /// lethal or unknown cells, with every state on the way within this distance of the start,
  /// until the footprint is free (the rule: StartEscape in start_escape.h). The search starts
  /// from every collision-free state so reached, at its escape cost: the bounds are relative to
  /// the optimum of that relaxed problem. A collision-free start is planned from as it is,
  /// whatever the tolerance. Forward searches only (backward_search refuses a start in
  /// collision, saying so).
  double tolerance = 0.0;
  /// >= 1: an escape motion costs this times what it costs across the costliest free cells
  /// (cost 252), so that paths leave a collision by the shortest way out.
  double penalty = 2.0;
};

/// Why a query was refused before searching.
enum class QueryError {
  kNone,
  kStartNotFinite,
  kGoalNotFinite,
  kStartOutOfMap,
  kGoalOutOfMap,
  kStartInCollision,
  kGoalInCollision,
  /// With a goal tolerance: the goal is in collision and the collision-free poses within the
  /// tolerance are all provably out of the start's reach.
  kGoalUnreachable,
};
/// One improved solution on the lattice.
struct LatticeSolution {
  Solution search;            ///< ids, cost (units), bounds, timing, iteration, weights
  std::vector<Pose2D> poses;  ///< the path in the map frame, intermediate poses included
  /// search.elapsed_s plus the time this plan() call spent before the search: computing
  /// heuristic grids and, with a goal tolerance, choosing the goal.
  double elapsed_total_s = 0.0;
  /// With a start escape (PlanResult::start_escaped): poses[0 .. escape_poses) leave the
  /// start's collision, and poses[escape_poses - 1] is the path's first collision-free pose;
  /// escape_cost (units, in search.cost) is what those motions cost. 0 without an escape.
  std::size_t escape_poses = 0;
  Cost escape_cost = 0;
};

/// With no path: what proved it.
enum class NoPathProof {
  kNone,           ///< not proven (another status, or a solution)
  kSearch,         ///< the search ran out of states its heuristics did not rule out
  kStartEnclosed,  ///< a walk found every state the start reaches, the goal none of them
  kGoalEnclosed,   ///< a walk found every state that reaches the goal, the start none of them
};

/// Where a query's heuristic grids came from.
enum class HeuristicSource {
  kNone,      ///< none was asked for: the query ended before them (an error, a dead end, a stop)
  kCached,    ///< the cache (or another call computing them at the same time)
  kComputed,  ///< computed for this query
  kRepaired,  ///< repaired from the grids of the planner this one was built from
};

struct PlanResult {
  QueryError error = QueryError::kNone;
  /// Human-readable reason when error != kNone; when goal_substituted, what replaced the goal.
  std::string message;
  SearchSummary search;  ///< how the search ended (status, expansions, memory, its time)
  /// Every improved solution in order (back() is the best): state ids, cost, bounds and poses.
  std::vector<LatticeSolution> solutions;
  /// Seconds this call spent computing the goal's heuristic grids, or waiting for another call
  /// computing them (0 when they were cached);
  /// it counts against limits.time_limit_s.
  double heuristic_seconds = 0.0;
  HeuristicSource heuristic_source = HeuristicSource::kNone;
  /// The pose the search plans to: the centre of the goal's cell with the goal's heading bin
  /// or, when a goal tolerance replaced an obstructed goal, that substitute; with any heading,
  /// the heading of the last solution's end (if there is none, the goal's or a collision-free
  /// one). Set once it is known: always when error is kNone, unless a stop came while the
  /// substitute was chosen.
  std::optional<Pose2D> planned_goal;
  /// True when the goal was in collision and a goal tolerance replaced it by planned_goal
  /// (message then says so); the solutions' bounds are relative to the optimal cost to
  /// planned_goal.
  bool goal_substituted = false;
  /// Seconds spent choosing that substitute; like heuristic_seconds, they count against
  /// limits.time_limit_s.
  double goal_seconds = 0.0;
  /// True when the start was in collision and StartOptions let the paths leave it: each
  /// solution's path begins with its escape (LatticeSolution::escape_poses), message says how the
  /// last one left, and the bounds are relative to the optimal cost of the relaxed problem (the
  /// escape motions from the start allowed). Set once the escape is found.
  bool start_escaped = false;
  bool hasSolution() const { return !solutions.empty(); }
  const LatticeSolution& best() const { return solutions.back(); }
  /// The search's view of the solutions (LatticeSolution::search), in order.
  std::vector<const Solution*> searchSolutions() const {
    std::vector<const Solution*> out;
    for (const LatticeSolution& s : solutions) out.push_back(&s.search);
    return out;
  }
  /// Seconds before the search: the escape, the goal choice and the heuristics.
  double setupSeconds() const { return escape_seconds + goal_seconds + heuristic_seconds; }
  /// Seconds of the whole call: setupSeconds() and the search.
  double totalSeconds() const { return setupSeconds() + search.elapsed_s; }

  /// How the last solution left the start's collision (empty without an escape).
  std::string escape_message;
  /// With search.status kNoSolution: what proved that no path exists; with a walk
  /// (goal_reachability.h), how many lattice states (cell and heading) the enclosed side holds,
  /// else 0; and no_path_reason says it for a user, e.g. "proven from the goal's side: only 2006
  /// lattice states (cell and heading; the goal's own included) lead to the goal, and the start
  /// is none of them". Empty, kNone and 0 otherwise.
  NoPathProof no_path = NoPathProof::kNone;
  std::size_t enclosed_states = 0;
  std::string no_path_reason;
  /// Seconds spent finding the escapes (they count against limits.time_limit_s too).
  double escape_seconds = 0.0;
};

class LatticeGraph;

/// A lattice planner for one map and one robot. Construction does the per-map work (loads or
/// generates primitives, checks them against the map, precomputes footprint sweeps, builds the
/// maps the heuristics need); heuristic grids are computed per goal and cached.
/// plan() may be called from several threads at once.
class LatticePlanner {
 public:
  /// Throws LatticeError when the map, primitives or robot are unusable: among them a robot
  /// whose inscribed circle is wider than the map, and footprint sweeps of more than
  /// kMaxSweptCells cells (refused before any sweep is computed).
  LatticePlanner(std::shared_ptr<const GridMap> map, const LatticeConfig& config);
  /// The same, honouring `limits`: its cancel flag and its time
  /// budget (counted from this call) stop the per-map work, and a per-map memory estimate
  /// above max_memory_bytes refuses it before it starts; each throws SetupStopped.
  /// max_expansions and max_states do not apply.
  LatticePlanner(std::shared_ptr<const GridMap> map, const LatticeConfig& config,
                 const SearchLimits& limits);
  /// The planner of `map`, a version of previous.map() whose cells differ only inside
  /// `changed` (same size, resolution and origin; checked, else LatticeError): the same result
  /// as the constructor above with previous.config(), built from `previous` by recomputing only
  /// what the change can reach (the robot's primitives and footprint sweeps are copied, the
  /// clearance and openings recomputed near `changed`). previous's cached heuristic grids are
  /// kept and repaired on the first query to their goal (LatticeConfig::Cache::repair).
  LatticePlanner(const LatticePlanner& previous, std::shared_ptr<const GridMap> map,
                 const CellRect& changed);
  ~LatticePlanner();
  LatticePlanner(const LatticePlanner&) = delete;
  LatticePlanner& operator=(const LatticePlanner&) = delete;

  const GridMap& map() const;
  const LatticeConfig& config() const;

  /// Checks start and goal (finite, inside the map, footprint collision-free).
  QueryError checkQuery(const Pose2D& start, const Pose2D& goal, std::string* message) const;

  /// Plans from start to goal. Query errors are returned in PlanResult (no search is run);
  /// every improved solution is passed to on_solution as soon as it is found. The cancel flag
  /// and time budget of `limits` also stop the computation of a new goal's heuristic grids
  /// (status kCancelled / kTimeLimit, no solution; the grids are then not cached).
  PlanResult plan(const Pose2D& start, const Pose2D& goal, const PlannerConfig& algorithm,
                  const SearchLimits& limits,
                  const std::function<void(const LatticeSolution&)>& on_solution = {});
  /// The same with GoalOptions (a goal tolerance, any goal heading): see there. The tolerance
  /// must be finite and >= 0, else std::invalid_argument.
  PlanResult plan(const Pose2D& start, const Pose2D& goal, const GoalOptions& goal_options,
                  const PlannerConfig& algorithm, const SearchLimits& limits,
                  const std::function<void(const LatticeSolution&)>& on_solution = {});

  /// Builds, in parallel threads, the kinematic tables (kinematic_table.h) that queries in the
  /// configured direction need, so that no query pays for them. They are shared by every
  /// planner with the same primitives and cost model, so only the first planner builds them.
  /// Honours limits' cancel flag and time budget: false if stopped first (a later query then
  /// builds what is missing). Returns true at once when there are no tables.
  bool prepareKinematicTables(const SearchLimits& limits = SearchLimits()) const;
  /// The same for one query only: the table its goal (searching backward, its start) needs,
  /// e.g. for a process that plans once (amha plan).
  bool prepareKinematicTables(const Pose2D& start, const Pose2D& goal,
                              const GoalOptions& goal_options,
                              const SearchLimits& limits = SearchLimits()) const;
  /// Bytes of the kinematic tables built so far (shared; 0 without tables).
  std::size_t kinematicTableBytes() const;
  /// The same with StartOptions (an escape from a start in collision): see there. The start
  /// tolerance must be finite and >= 0 and the penalty finite and >= 1, else
  /// std::invalid_argument.
  PlanResult plan(const Pose2D& start, const Pose2D& goal, const StartOptions& start_options,
                  const GoalOptions& goal_options, const PlannerConfig& algorithm,
                  const SearchLimits& limits,
                  const std::function<void(const LatticeSolution&)>& on_solution = {});

  /// The footprint polygon placed at a pose (map frame), for drawing and markers.
  std::vector<std::array<double, 2>> footprintAt(const Pose2D& pose) const;

  /// The lattice it plans on: its map, primitives, footprint sweeps and edge costs (e.g. for
  /// PathSmoother, path_smoother.h). Lives as long as the planner.
  const LatticeGraph& graph() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The search configuration the lattice planner uses by default (CLI, server, benchmarks):
/// amha::defaultConfig(algorithm), except for A-MHA*, whose paper preset (w1 = w2 = 5, steps of
/// 0.5) gives a first path 10-15 % above the optimum and then nothing until the proof. Here it
/// starts at w1 = 1.03, w2 = 5 (with the kinematic inadmissible heuristics the first path is then
/// within about 1 % of the optimum), goes on with w1 = 2 if that first iteration has expanded
/// 10,000 states without a path (hard queries, where a w1 near 1 crawls), then straight to the
/// proof (certified schedule, ratio 0: intermediate iterations cost more than they find,
/// docs/lattice.md), and publishes every cheaper path and every halving of the certified
/// bound's gap as the proof goes on.
PlannerConfig defaultPlannerConfig(Algorithm algorithm);

const char* queryErrorName(QueryError e);
const char* noPathProofName(NoPathProof p);
const char* heuristicSourceName(HeuristicSource s);

}  // namespace lattice
}  // namespace amha
