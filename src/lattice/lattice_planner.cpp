// LatticePlanner: the facade over the lattice graph, the per-goal heuristic cache and the search.
#include "amha_planner/lattice/lattice_planner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <future>
#include <limits>
#include <list>
#include <mutex>
#include <new>
#include <stdexcept>
#include <thread>

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "amha_planner/lattice/detail/backward_bound.h"
#include "amha_planner/lattice/detail/displacement_grid.h"
#include "amha_planner/lattice/detail/goal_reachability.h"
#include "amha_planner/lattice/detail/goal_tolerance.h"
#include "amha_planner/lattice/detail/heuristic_grids.h"
#include "amha_planner/lattice/detail/lattice_problem.h"
#include "amha_planner/lattice/detail/start_escape.h"
#include "amha_planner/lattice/lattice_graph.h"

namespace amha {
namespace lattice {

struct LatticePlanner::Impl {
  std::shared_ptr<const GridMap> map;
  std::unique_ptr<LatticeGraph> graph;
  std::unique_ptr<HeuristicGridBuilder> builder;
  /// The displacement grid's moves, levels and clearance (null: not wanted, or one core).
  std::unique_ptr<DisplacementGrid> displacement;
  void buildDisplacement() {
    const LatticeConfig::Heuristics& h = graph->config().heuristics;
    if (h.grid_anchor && h.displacement_grid && std::thread::hardware_concurrency() >= 2)
      displacement.reset(new DisplacementGrid(*graph));
  }

  /// Which grids: a goal (or, searching backward, a start) and which kinds were wanted.
  struct GoalKey {
    int x, y, heading;
    bool inadmissible, backward;
    bool operator==(const GoalKey& o) const {
      return x == o.x && y == o.y && heading == o.heading && inadmissible == o.inadmissible &&
             backward == o.backward;
    }
  };
  struct CacheEntry {
    GoalKey key;
    std::uint64_t serial;  // tells this entry from a later one for the same goal
    std::shared_future<std::shared_ptr<const GoalHeuristics>> grids;
  };
  std::mutex mutex;
  std::list<CacheEntry> cache;  // most recently used first
  std::uint64_t next_serial = 0;
  /// Grids of the planners this one was built from, for goals it has not computed yet, with
  /// the areas changed since (LatticeConfig::Cache::repair): repaired on first use.
  struct StaleEntry {
    GoalKey key;
    std::shared_ptr<const GoalHeuristics> grids;
    std::vector<CellRect> changed;
  };
  // The previous planner's most recently used first; with `cache`, at most
  // heuristic_cache_size goals (guarded by mutex).
  std::list<StaleEntry> stale;
  /// A chain of more updates than this is not repaired: its areas may cover the map.
  static constexpr std::size_t kMaxChangedAreas = 32;

  std::size_t capacity() const { return static_cast<std::size_t>(graph->config().cache.size); }

  /// Takes the grids of `previous` (cached or stale) over as stale entries, `changed` added.
  void inheritGrids(Impl& previous, const CellRect& changed) {
    std::lock_guard<std::mutex> lock(previous.mutex);
    auto add = [&](const StaleEntry& e) {
      if (stale.size() >= capacity() || e.changed.size() >= kMaxChangedAreas) return;
      for (const StaleEntry& s : stale) {
        if (s.key == e.key) return;
      }
      stale.push_back(e);
      if (!changed.empty()) stale.back().changed.push_back(changed);
    };
    for (const CacheEntry& e : previous.cache) {
      // Grids still being computed (or stopped, or failed) are not waited for.
      if (e.grids.wait_for(std::chrono::seconds(0)) != std::future_status::ready) continue;
      std::shared_ptr<const GoalHeuristics> grids;
      try {
        grids = e.grids.get();
      } catch (...) {
        continue;
      }
      if (grids) add(StaleEntry{e.key, grids, {}});
    }
    for (const StaleEntry& e : previous.stale) add(e);
  }

  /// The goal cell's grids: from the cache, or computed now (once, even if several threads ask
  /// at the same time). Null when `stop` (cancel flag, deadline) stopped this call first; a
  /// computation stopped that way is not cached, and threads that were waiting for it compute
  /// the grids themselves. `seconds` receives the time spent here computing or waiting for them.
  /// Computed here, they are handed out once search_start's distances are final (compute()).
  std::shared_ptr<const GoalHeuristics> heuristicsFor(int x, int y, int heading, bool inadmissible,
                                                      bool backward, const StopCondition& stop,
                                                      double* seconds, HeuristicSource* source,
                                                      std::pair<int, int> search_start) {
    const GoalKey key{x, y, heading, inadmissible, backward};
    const auto t0 = std::chrono::steady_clock::now();
    auto since = [&] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    };
    *seconds = 0.0;
    *source = HeuristicSource::kCached;
    for (;;) {
      std::promise<std::shared_ptr<const GoalHeuristics>> promise;
      std::shared_future<std::shared_ptr<const GoalHeuristics>> future;
      std::uint64_t serial = 0;
      // A stale entry for this goal is taken out of the list: the repair may spend its grids.
      std::shared_ptr<const GoalHeuristics> stale_grids;
      std::vector<CellRect> stale_changed;
      {
        std::lock_guard<std::mutex> lock(mutex);
        for (auto it = cache.begin(); it != cache.end(); ++it) {
          if (it->key == key) {
            cache.splice(cache.begin(), cache, it);
            future = it->grids;
            serial = it->serial;
            break;
          }
        }
        if (!future.valid()) {
          serial = next_serial++;
          cache.push_front(CacheEntry{key, serial, promise.get_future().share()});
          while (cache.size() > capacity()) cache.pop_back();
          for (auto it = stale.begin(); it != stale.end(); ++it) {
            if (it->key == key) {
              stale_grids = std::move(it->grids);
              stale_changed = std::move(it->changed);
              stale.erase(it);
              break;
            }
          }
          while (!stale.empty() && cache.size() + stale.size() > capacity()) stale.pop_back();
        }
      }
      auto forget = [&] {
        std::lock_guard<std::mutex> lock(mutex);
        cache.remove_if([&](const CacheEntry& e) { return e.serial == serial; });
      };
      if (future.valid()) {
        // Another call computes them: wait, but not beyond our own cancel or deadline.
        if (future.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
          while (future.wait_for(std::chrono::milliseconds(2)) != std::future_status::ready) {
            if (stop.requested()) {
              *seconds = since();
              return nullptr;
            }
          }
          *seconds = since();
        }
        if (auto grids = future.get()) {
          // Stopped early for another search (GoalHeuristics::stopBeyond), its grids read as
          // weak bounds away from that search's start: computed again for this one.
          if (!grids->anyAbandoned()) return grids;
          forget();
        }
        continue;  // that call was stopped: compute them here
      }
      try {
        // Moved in: if no older planner or running search holds them, they are repaired in
        // place (a stopped repair then leaves nothing to repair later: the next query computes).
        const bool repairing = stale_grids != nullptr;
        auto grids = repairing ? builder->repair(std::move(stale_grids), stale_changed,
                                                 inadmissible, 0, backward, &stop)
                               : builder->compute(x, y, heading, inadmissible, 0, backward, &stop,
                                                  &search_start);
        if (!grids) forget();
        promise.set_value(grids);
        *seconds = since();
        *source = repairing ? HeuristicSource::kRepaired : HeuristicSource::kComputed;
        return grids;
      } catch (...) {
        promise.set_exception(std::current_exception());
        forget();
        throw;
      }
    }
  }

  /// Appends the poses of `a` from `from` after its first (which ends the poses so far).
  void appendMotion(const LatticeState& from, const LatticeAction& a,
                    std::vector<Pose2D>& poses) const {
    const MotionPrimitive& prim = graph->primitives().primitives[a.primitive];
    for (std::size_t i = 1; i < prim.poses.size(); ++i)
      poses.push_back(graph->cellPoseToMap(from.x, from.y, prim.poses[i]));
  }

  /// The poses of a solution path, each motion the action its edge's label names (the search
  /// found them when it costed the path: no action is looked up again).
  std::vector<Pose2D> posesOf(const LatticeProblem& problem, const Solution& solution) const {
    const std::vector<StateId>& path = solution.path;
    std::vector<Pose2D> poses;
    if (path.empty()) return poses;
    if (solution.edge_labels.size() + 1 != path.size())
      throw std::logic_error("lattice: a solution's edges are not labelled");
    const LatticeState s0 = problem.state(path.front());
    poses.push_back(graph->stateToPose(s0.x, s0.y, s0.heading));
    for (std::size_t k = 1; k < path.size(); ++k) {
      const std::uint32_t label = solution.edge_labels[k - 1];
      if (label >= graph->actions().size())
        throw std::logic_error("lattice: solution uses a transition that is not an action");
      const LatticeAction* a = &graph->actions()[label];
      appendMotion(problem.state(path[k - 1]), *a, poses);
    }
    return poses;
  }

  /// Puts the escape from `start` to the solution's first state (an exit) before its poses.
  void prependEscape(const StartEscape& escape, const LatticeState& start,
                     const LatticeState& first, LatticeSolution& solution) const {
    const StartEscape::Exit* exit = escape.exitAt(first);
    if (exit == nullptr)
      throw std::logic_error("lattice: a solution starts at a state no escape reaches");
    std::vector<Pose2D> poses{graph->stateToPose(start.x, start.y, start.heading)};
    for (const StartEscape::Step& step : escape.path(*exit))
      appendMotion(step.from, *step.action, poses);
    solution.escape_poses = poses.size();
    solution.escape_cost = exit->cost;
    poses.insert(poses.end(), solution.poses.begin() + 1, solution.poses.end());
    solution.poses = std::move(poses);
  }
};

namespace {

/// The cancel flag and the time budget of `limits`, from now.
StopCondition stopFor(const SearchLimits& limits) {
  return StopCondition(limits.cancel, limits.time_limit_s);
}

/// Which kinematic tables a search uses: to the goal, or searching backward from the start.
KinematicTables::Direction tableDirection(bool backward) {
  return backward ? KinematicTables::Direction::kFromStart : KinematicTables::Direction::kToGoal;
}

}  // namespace

LatticePlanner::LatticePlanner(std::shared_ptr<const GridMap> map, const LatticeConfig& config)
    : LatticePlanner(std::move(map), config, SearchLimits()) {}

LatticePlanner::LatticePlanner(std::shared_ptr<const GridMap> map, const LatticeConfig& config,
                               const SearchLimits& limits)
    : impl_(new Impl) {
  const StopCondition stop = stopFor(limits);
  impl_->map = map;
  impl_->graph.reset(
      new LatticeGraph(std::move(map), config, GraphLimits{&stop, limits.max_memory_bytes}));
  throwIfStopped(&stop, "heuristic tables");
  impl_->builder.reset(new HeuristicGridBuilder(*impl_->graph));
  impl_->buildDisplacement();
}

LatticePlanner::LatticePlanner(const LatticePlanner& previous, std::shared_ptr<const GridMap> map,
                               const CellRect& changed)
    : impl_(new Impl) {
  impl_->map = map;
  impl_->graph.reset(new LatticeGraph(*previous.impl_->graph, std::move(map), changed));
  impl_->builder.reset(new HeuristicGridBuilder(*previous.impl_->builder, *impl_->graph));
  impl_->buildDisplacement();
  if (impl_->graph->config().cache.repair)
    impl_->inheritGrids(*previous.impl_, impl_->graph->recomputed());
}

LatticePlanner::~LatticePlanner() = default;

const GridMap& LatticePlanner::map() const { return *impl_->map; }
const LatticeConfig& LatticePlanner::config() const { return impl_->graph->config(); }

namespace {
std::string poseText(const Pose2D& p) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "(%.3f, %.3f, %.3f)", p.x, p.y, p.theta);
  return buf;
}
}  // namespace

namespace {

/// checkQuery's verdict on one pose (the start if is_start, else the goal); `why` says why.
QueryError checkPose(const LatticeGraph& g, const Pose2D& p, bool is_start, std::string* why) {
  const char* name = is_start ? "start" : "goal";
  int x = 0, y = 0, h = 0;
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.theta)) {
    *why = std::string(name) + " pose is not finite";
    return is_start ? QueryError::kStartNotFinite : QueryError::kGoalNotFinite;
  }
  if (!g.poseToState(p, &x, &y, &h)) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  " is outside the map (%d x %d cells of %.3f m, origin (%.3f, %.3f, %.3f))",
                  g.width(), g.height(), g.map().resolution, g.map().origin_x, g.map().origin_y,
                  g.map().origin_yaw);
    *why = std::string(name) + " " + poseText(p) + buf;
    return is_start ? QueryError::kStartOutOfMap : QueryError::kGoalOutOfMap;
  }
  if (!g.stateValid(x, y, h)) {
    *why = std::string(name) + " " + poseText(p) + " is in collision (cell " + std::to_string(x) +
           ", " + std::to_string(y) + ", heading " + std::to_string(h) + ": cell cost " +
           std::to_string(g.map().at(x, y)) +
           " or the footprint touches an obstacle or leaves the map)";
    return is_start ? QueryError::kStartInCollision : QueryError::kGoalInCollision;
  }
  why->clear();
  return QueryError::kNone;
}

}  // namespace

QueryError LatticePlanner::checkQuery(const Pose2D& start, const Pose2D& goal,
                                      std::string* message) const {
  std::string why;
  QueryError e = checkPose(*impl_->graph, start, true, &why);
  if (e == QueryError::kNone) e = checkPose(*impl_->graph, goal, false, &why);
  if (message != nullptr) *message = why;
  return e;
}

namespace {

/// Fills result's no_path, enclosed_states and no_path_reason for a search that ended with
/// kNoSolution: by a walk from its goal's side (search.goal_side_proof; the robot's start when
/// searching backward), which counted `walked` states, or by running out of states.
void describeNoPath(const SearchSummary& search, bool backward, std::size_t walked,
                    PlanResult* result) {
  const std::string from = backward ? "goal" : "start", to = backward ? "start" : "goal";
  if (!search.goal_side_proof) {
    result->no_path = NoPathProof::kSearch;
    // The heuristics are computed from the search's goal: a state they give infinity cannot
    // reach it, and is never expanded.
    result->no_path_reason = search.expansions == 0
                                 ? "proven by the heuristics, computed from the " + to +
                                       "'s side: the " + from + " cannot reach the " + to
                                 : "proven by the search: it ran out of states from the " + from +
                                       " after " + std::to_string(search.expansions) +
                                       (search.expansions == 1 ? " expansion" : " expansions") +
                                       " (its heuristics, computed from the " + to +
                                       "'s side, rule out the others)";
    return;
  }
  // The walk starts at the search's goal (`to`): that end is enclosed, `from` none of its states.
  const bool goal_enclosed = !backward;
  result->no_path = goal_enclosed ? NoPathProof::kGoalEnclosed : NoPathProof::kStartEnclosed;
  result->enclosed_states = walked;
  const std::string proven = "proven from the " + to + "'s side: ";
  if (walked <= 1) {
    result->no_path_reason = proven + "no valid motion " +
                             (goal_enclosed ? "ends in the goal's" : "leaves the start's") +
                             " lattice state (cell and heading)";
    return;
  }
  result->no_path_reason = proven + "only " + std::to_string(walked) +
                           " lattice states (cell and heading; the " + to + "'s own included) " +
                           (goal_enclosed ? "lead to the goal" : "can be reached from the start") +
                           ", and the " + from + " is none of them";
}

}  // namespace

PlanResult LatticePlanner::plan(const Pose2D& start, const Pose2D& goal,
                                const PlannerConfig& algorithm, const SearchLimits& limits,
                                const std::function<void(const LatticeSolution&)>& on_solution) {
  return plan(start, goal, GoalOptions(), algorithm, limits, on_solution);
}

namespace {

/// The state plan() searches to, as `options` ask: the goal pose's state; with any heading, a
/// collision-free heading of its cell; with a tolerance, the substitute for a goal in
/// collision. `result` holds checkQuery's verdict on entry; false if it is final (a query
/// error, or `stop` came first: then result.search.status says which).
bool chooseGoal(const LatticeGraph& g, const LatticeState& s, const Pose2D& goal,
                const GoalOptions& options, const StopCondition& stop,
                std::chrono::steady_clock::time_point since, PlanResult& result, LatticeState* t) {
  g.poseToState(goal, &t->x, &t->y, &t->heading);
  if (result.error == QueryError::kGoalInCollision && options.any_heading) {
    // Another heading may be free there; the search takes any.
    for (int h = 0; h < g.numHeadings() && result.error != QueryError::kNone; ++h) {
      if (!g.stateValid(t->x, t->y, h)) continue;
      t->heading = h;
      result.error = QueryError::kNone;
      result.message.clear();
    }
    if (result.error != QueryError::kNone) result.message += " at every heading";
  }
  if (result.error == QueryError::kNone) return true;
  if (result.error != QueryError::kGoalInCollision || options.tolerance <= 0.0) return false;
  const GoalChoice c = nearestReachableGoal(g, goal, options.tolerance, s.x, s.y, &stop);
  result.goal_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
  char tol[64];
  std::snprintf(tol, sizeof tol, "%.3f m", options.tolerance);
  switch (c.outcome) {
    case GoalChoice::Outcome::kStopped:
      result.error = QueryError::kNone;
      result.message.clear();
      result.search.status = stoppedStatus(stop);
      return false;
    case GoalChoice::Outcome::kNoFreePose:
      result.message +=
          "; no collision-free pose lies within the goal tolerance of " + std::string(tol);
      return false;
    case GoalChoice::Outcome::kNoneReachable:
      result.error = QueryError::kGoalUnreachable;
      result.message += "; the collision-free poses within the goal tolerance of " +
                        std::string(tol) +
                        " all lie in free space that the start's does not connect to";
      return false;
    case GoalChoice::Outcome::kFound:
      break;
  }
  *t = LatticeState{c.x, c.y, c.heading};
  result.error = QueryError::kNone;
  result.goal_substituted = true;
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "; planning to the nearest reachable collision-free pose instead, %s, %.3f m and "
                "%.3f rad from it (goal tolerance %s)",
                poseText(g.stateToPose(c.x, c.y, c.heading)).c_str(), c.distance,
                c.heading_difference, tol);
  result.message += buf;
  return true;
}

/// The escapes from start state `s`, in collision (`collision` says how), as StartOptions
/// allow. False if that is final: no escape (result.error kStartInCollision), or `stop` came first
/// (result.search.status says which).
bool leaveStart(const LatticeGraph& g, const LatticeState& s, const StartOptions& options,
                const StopCondition& stop, const std::string& collision, PlanResult& result,
                std::unique_ptr<StartEscape>* escape) {
  if (g.config().backward_search) {
    result.error = QueryError::kStartInCollision;
    result.message =
        collision + "; a start escape needs a forward search, and backward_search is set";
    return false;
  }
  const auto t0 = std::chrono::steady_clock::now();
  escape->reset(new StartEscape(g, s, options.tolerance, options.penalty, &stop));
  result.escape_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  switch ((*escape)->outcome()) {
    case StartEscape::Outcome::kStopped:
      result.error = QueryError::kNone;
      result.message.clear();
      result.search.status = stoppedStatus(stop);
      return false;
    case StartEscape::Outcome::kNoExit: {
      char buf[240];
      std::snprintf(
          buf, sizeof buf,
          "; no collision-free pose within the start tolerance of %.3f m can be reached "
          "by motions across inscribed cells and the %zu obstacle cell(s) under the robot",
          options.tolerance, (*escape)->cellsUnderStart());
      result.error = QueryError::kStartInCollision;
      result.message = collision + buf;
      return false;
    }
    case StartEscape::Outcome::kFound:
      break;
  }
  result.start_escaped = true;
  return true;
}

/// How `solution` (null: none yet) left the start's collision, for PlanResult::escape_message.
std::string describeEscape(const std::string& collision, const StartEscape& escape,
                           const StartOptions& options, const LatticeSolution* solution) {
  char buf[400];
  if (solution == nullptr) {
    std::snprintf(buf, sizeof buf,
                  "; %zu collision-free pose(s) can be reached by leaving it within the start "
                  "tolerance of %.3f m, but no path was found from them",
                  escape.exits().size(), options.tolerance);
    return collision + buf;
  }
  const std::vector<Pose2D>& p = solution->poses;
  double length = 0.0;
  for (std::size_t k = 1; k < solution->escape_poses; ++k)
    length += std::hypot(p[k].x - p[k - 1].x, p[k].y - p[k - 1].y);
  std::snprintf(buf, sizeof buf,
                "; the path leaves it by %.3f m of motion (escape cost %.3f) to the collision-free "
                "pose %s, crossing only inscribed cells and the %zu obstacle cell(s) under the "
                "robot (start tolerance "
                "%.3f m, escape penalty %g); its bounds are relative to the optimum with such an "
                "escape allowed",
                length, static_cast<double>(solution->escape_cost) / kCostUnitsPerMetre,
                poseText(p[solution->escape_poses - 1]).c_str(), escape.cellsUnderStart(),
                options.tolerance, options.penalty);
  return collision + buf;
}

/// How many states deadEnd walks from each end at most: a pocket of a few states (a goal only
/// a couple of motions enter, a start that can only creep into a corner) is told at once, for
/// about a thousand edge tests per end on a query that has none.
constexpr std::size_t kDeadEndStates = 64;

/// True, with `result` saying so, if at most kDeadEndStates lattice states lead to goal state
/// `t` (with any heading: to any state of its cell) and start state `s` is none of them, or at
/// most that many can be reached from `s` and the goal is none of them: then no path exists,
/// whatever the map beyond. Walks only those states (their edge tests, nothing more). Asked
/// before the heuristic grids, which would otherwise cover the goal's whole free space to find
/// the start cut off (on the Smac benchmark's 2000 x 2000 random map, 0.03-0.10 s and 6-18 MB
/// for such a query); larger pockets are left to the search's own walk (goalUnreachable).
bool deadEnd(const LatticeGraph& g, const LatticeState& s, const LatticeState& t, bool any_heading,
             PlanResult* result) {
  std::vector<LatticeState> goals;
  for (int h = 0; h < g.numHeadings(); ++h) {
    if (any_heading || h == t.heading) goals.push_back(LatticeState{t.x, t.y, h});
  }
  auto is_start = [&](const LatticeState& v) { return v == s; };
  auto is_goal = [&](const LatticeState& v) {
    return v.x == t.x && v.y == t.y && (any_heading || v.heading == t.heading);
  };
  // Told as the search's own walks are (describeNoPath: a walk from the goal, or from the start
  // as a backward search's).
  SearchSummary walk;
  walk.goal_side_proof = true;
  std::size_t walked = 0;
  const std::size_t budget = std::max(kDeadEndStates, goals.size());
  if (exploreReachable(g, goals, true, is_start, budget, {}, &walked) == Reachability::kEnclosed) {
    describeNoPath(walk, /*backward=*/false, walked, result);
    if (any_heading && walked == goals.size())  // only the seeds: say it of the cell
      result->no_path_reason =
          "proven from the goal's side: no valid motion ends in the goal's cell, at any heading";
  } else if (exploreReachable(g, {s}, false, is_goal, budget, {}, &walked) ==
             Reachability::kEnclosed) {
    describeNoPath(walk, /*backward=*/true, walked, result);
  } else {
    return false;
  }
  result->search.status = SearchStatus::kNoSolution;
  result->search.goal_side_proof = true;  // a walk's proof, not a search's
  return true;
}

}  // namespace

PlanResult LatticePlanner::plan(const Pose2D& start, const Pose2D& goal,
                                const GoalOptions& goal_options, const PlannerConfig& algorithm,
                                const SearchLimits& limits,
                                const std::function<void(const LatticeSolution&)>& on_solution) {
  return plan(start, goal, StartOptions(), goal_options, algorithm, limits, on_solution);
}

PlanResult LatticePlanner::plan(const Pose2D& start, const Pose2D& goal,
                                const StartOptions& start_options, const GoalOptions& goal_options,
                                const PlannerConfig& algorithm, const SearchLimits& limits,
                                const std::function<void(const LatticeSolution&)>& on_solution) {
  if (!std::isfinite(goal_options.tolerance) || goal_options.tolerance < 0.0) {
    throw std::invalid_argument("the goal tolerance must be finite and >= 0 (metres)");
  }
  if (!std::isfinite(start_options.tolerance) || start_options.tolerance < 0.0) {
    throw std::invalid_argument("the start tolerance must be finite and >= 0 (metres)");
  }
  if (!std::isfinite(start_options.penalty) || start_options.penalty < 1.0) {
    throw std::invalid_argument("the start escape penalty must be finite and >= 1");
  }
  const bool any_heading = goal_options.any_heading;
  // The goal choice and the grids honour the cancel flag and the time budget too (seconds on
  // a big map).
  const StopCondition stop = stopFor(limits);
  const LatticeGraph& g = *impl_->graph;
  PlanResult result;
  result.error = checkQuery(start, goal, &result.message);
  // A start in collision may be left under StartOptions; the goal still gets its checks.
  std::string start_collision;
  if (result.error == QueryError::kStartInCollision && start_options.tolerance > 0.0) {
    start_collision = result.message;
    result.error = checkPose(g, goal, false, &result.message);
  }
  // Only a goal in collision may still be planned for: then both poses are finite and inside
  // the map (and the start valid, or to be left), which poseToState needs.
  if (result.error != QueryError::kNone && result.error != QueryError::kGoalInCollision)
    return result;
  std::unique_ptr<Planner> planner = makePlanner(algorithm);  // throws for invalid weights
  LatticeState s, t;
  g.poseToState(start, &s.x, &s.y, &s.heading);
  std::unique_ptr<StartEscape> escape;
  if (!start_collision.empty() &&
      !leaveStart(g, s, start_options, stop, start_collision, result, &escape))
    return result;
  // With an escape, goals are reachable if they are from its cheapest exit.
  const LatticeState reach_from =
      escape ? std::min_element(escape->exits().begin(), escape->exits().end(),
                                [](const auto& a, const auto& b) { return a.cost < b.cost; })
                   ->state
             : s;
  if (!chooseGoal(g, reach_from, goal, goal_options, stop, std::chrono::steady_clock::now(), result,
                  &t))
    return result;
  result.planned_goal = g.stateToPose(t.x, t.y, t.heading);
  // (A start in collision begins at its escape's exits instead, which the search's own walk
  // from the goal asks about.)
  if (!escape && deadEnd(g, s, t, any_heading, &result)) return result;
  // Algorithms that read only the anchor do not need the inadmissible grids.
  const bool uses_inadmissible = algorithmSpecs(algorithm.algorithm).inadmissible_heuristics &&
                                 algorithm.max_inadmissible > 0 &&
                                 g.config().heuristics.num_inadmissible > 0;
  // Backward search runs from the goal to the start, with heuristics measured from the start.
  const bool backward = g.config().backward_search;
  const LatticeState from = backward ? t : s, to = backward ? s : t;
  // A goal of any heading has its own coarse distances (to the nearest of its headings).
  const int table_heading = any_heading && !backward ? kAnyHeading : to.heading;
  // The grids belong to the request's memory too: 4 bytes a padded cell for each grid it needs.
  const std::size_t padded = static_cast<std::size_t>(g.width() + 4) * (g.height() + 4);
  std::size_t grid_count = g.config().heuristics.grid_anchor ? 1 : 0;
  if (uses_inadmissible)
    grid_count += static_cast<std::size_t>(g.config().heuristics.num_inadmissible);
  if (grid_count * padded * sizeof(std::uint32_t) > limits.max_memory_bytes) {
    result.search.status = SearchStatus::kMemoryLimit;
    return result;
  }
  // The search may start once its first cell's distances are final (the rest of the grids are
  // completed alongside it).
  auto grids =
      impl_->heuristicsFor(to.x, to.y, table_heading, uses_inadmissible, backward, stop,
                           &result.heuristic_seconds, &result.heuristic_source, {from.x, from.y});
  if (!grids) {
    result.search.status = stoppedStatus(stop);
    return result;  // no search ran: search.elapsed_s stays 0, heuristic_seconds has the time
  }
  // The kinematic table at the goal (backward: from the start), built on first use.
  KinematicLookup kinematic;
  if (g.kinematicTables()) {
    double seconds = 0.0;
    kinematic =
        g.kinematicTables()->lookup(tableDirection(backward), table_heading, &stop, &seconds);
    result.heuristic_seconds += seconds;
    if (!kinematic.valid()) {
      result.search.status = stoppedStatus(stop);
      return result;
    }
  }
  LatticeProblem problem(g, grids, from, to,
                         uses_inadmissible ? g.config().heuristics.num_inadmissible : 0, backward,
                         any_heading, kinematic);
  if (escape) {
    std::vector<std::pair<LatticeState, Cost>> exits;
    for (const StartEscape::Exit& e : escape->exits()) exits.emplace_back(e.state, e.cost);
    problem.startAtExits(exits);
  }
  // The displacement grid, on a helper thread while the search runs: the search takes it up
  // when it is complete (LatticeProblem::upgradeHeuristics), and stops it when it returns first.
  // Only searches that can use it ask for it: A* (every 1024 expansions) at once, and the
  // anytime ones (their later iterations and proof) from their first path on, which it would
  // otherwise slow (by 8 % on Willow at 5 cm, competing with the search and the grids' helper).
  std::shared_ptr<DisplacementField> field;
  std::thread field_thread;
  const Algorithm algo = algorithm.algorithm;
  const bool anytime = algo == Algorithm::kAmhaStar || algo == Algorithm::kAraStar;
  // Its distances take 4 bytes a padded cell beside the grids, within the same memory cap.
  const bool room_for_field =
      impl_->displacement &&
      (grid_count * padded + impl_->displacement->cellCount()) * sizeof(std::uint32_t) <=
          limits.max_memory_bytes;
  if (room_for_field && grids->grids[0] != nullptr && (anytime || algo == Algorithm::kAStar)) {
    field = std::make_shared<DisplacementField>();
    problem.setDisplacementField(field);
  }
  auto launch_field = [&, grid = impl_->displacement.get()] {
    if (!field || field_thread.joinable()) return;
    field_thread = std::thread([field = field, grid, to, from, backward, stop] {
      // Below the search in priority: where the grids' helper still runs, it would slow both.
      setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 10);
      try {
        if (grid->compute(to.x, to.y, !backward, from.x, from.y, &field->bound, field.get(),
                          &field->abandon, &stop))
          field->ready.store(true, std::memory_order_release);
      } catch (const std::bad_alloc&) {
        // No memory for it: the search goes on with the anchor it has.
      }
    });
  };
  if (algo == Algorithm::kAStar) launch_field();
  // The backward side of a bidirectional proof (backward_bound.h), from bidirectional_after_s
  // into the search on: a helper thread waits until then, builds the grids from the start (and
  // takes the start's kinematic table), and runs A* from the goal, which raises this search's
  // anchor as it goes. A forward search to one state only, on two cores or more.
  const double after_s = g.config().heuristics.bidirectional_after_s;
  const std::size_t states =
      static_cast<std::size_t>(g.width()) * g.height() * static_cast<std::size_t>(g.numHeadings());
  std::shared_ptr<BackwardBound> bidir;
  if (after_s >= 0.0 && !backward && !any_heading && !escape &&
      (anytime || algo == Algorithm::kAStar) && std::thread::hardware_concurrency() >= 2 &&
      (grid_count + 1) * padded * sizeof(std::uint32_t) + states * sizeof(std::uint32_t) <=
          limits.max_memory_bytes) {
    bidir = std::make_shared<BackwardBound>();
    problem.setBackwardBound(bidir);
  }
  std::thread bidir_thread;
  if (bidir) {
    const auto begin = std::chrono::steady_clock::now();
    SearchLimits backward_limits;
    backward_limits.cancel = &bidir->stop;
    backward_limits.max_memory_bytes = limits.max_memory_bytes / 2;  // beside this search's
    bidir_thread = std::thread([this, bb = bidir, s, t, begin, after_s, backward_limits] {
      setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 10);
      const LatticeGraph& graph = *impl_->graph;
      auto elapsed = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
      };
      // The search's end (whatever ends it) sets bb->stop: the grids and the table stop with it,
      // so that the search's result never waits for them.
      const StopCondition halt(&bb->stop, std::numeric_limits<double>::infinity());
      while (elapsed() < after_s) {
        if (halt.requested()) return;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
      try {
        double seconds = 0.0;
        HeuristicSource source;
        auto grids = impl_->heuristicsFor(s.x, s.y, s.heading, false, true, halt, &seconds, &source,
                                          {t.x, t.y});
        if (!grids) return;
        // Complete before either search reads them: a cell read before it is final waits.
        for (const auto& grid : grids->grids) {
          while (grid && !grid->complete()) {
            if (grid->progress->abandoned.load() || bb->stop.load(std::memory_order_relaxed))
              return;
            std::this_thread::sleep_for(std::chrono::microseconds(200));
          }
        }
        KinematicLookup kinematic;
        if (graph.kinematicTables()) {
          kinematic = graph.kinematicTables()->lookup(KinematicTables::Direction::kFromStart,
                                                      s.heading, &halt);
          if (!kinematic.valid()) return;
        }
        bb->width = graph.width();
        bb->headings = graph.numHeadings();
        bb->closed.reset(static_cast<std::size_t>(graph.width()) * graph.height() *
                         static_cast<std::size_t>(graph.numHeadings()));
        bb->start_anchor.reset(new LatticeProblem(graph, grids, t, s, 0, true, false, kinematic));
        LatticeProblem search(graph, grids, t, s, 0, true, false, kinematic);
        search.setBackwardSink(bb.get());
        bb->ready.store(true, std::memory_order_release);
        makePlanner(defaultPlannerConfig(Algorithm::kAStar))
            ->search(search, backward_limits, [](const Solution&) {});
      } catch (const std::exception&) {
        // No memory or a table refused: the forward search goes on with its own anchor.
      }
    });
  }
  // At scope exit: ask each helper thread to stop, and join it.
  struct JoinHelper {
    std::atomic<bool>* stop;  // set when the thread exists
    std::thread& thread;
    ~JoinHelper() {
      if (!thread.joinable()) return;
      stop->store(true, std::memory_order_relaxed);
      thread.join();
    }
  };
  const JoinHelper join_bidir{bidir ? &bidir->stop : nullptr, bidir_thread};
  const JoinHelper join_field{field ? &field->abandon : nullptr, field_thread};
  // Solution paths run start ... goal; an any-heading goal's virtual state ends them, and an
  // escape's virtual start begins them (its poses are put back by prependEscape).
  auto lattice_path = [&](Solution& sol) {
    std::vector<StateId>& path = sol.path;
    std::vector<std::uint32_t>& labels = sol.edge_labels;  // one per edge, in step with path
    if (backward) {
      std::reverse(path.begin(), path.end());
      std::reverse(labels.begin(), labels.end());  // a backward edge's label is its forward action
    }
    if (!path.empty() && path.back() == problem.virtualGoal()) {
      path.pop_back();
      if (!labels.empty()) labels.pop_back();
    }
    if (!path.empty() && path.front() == problem.virtualStart()) {
      path.erase(path.begin());
      if (!labels.empty()) labels.erase(labels.begin());
    }
  };
  SearchLimits remaining = limits;
  const double offset = result.setupSeconds();
  remaining.time_limit_s = std::max(0.0, limits.time_limit_s - offset);
  SolutionCallback cb = [&](const Solution& sol) {
    LatticeSolution ls;
    ls.search = sol;
    lattice_path(ls.search);
    ls.poses = impl_->posesOf(problem, ls.search);
    if (escape) impl_->prependEscape(*escape, s, problem.state(ls.search.path.front()), ls);
    ls.elapsed_total_s = sol.elapsed_s + offset;
    // The displacement grid may stop where keys reach this cost (DisplacementGrid::compute).
    if (field && sol.cost >= 0) {
      field->bound.store(std::min(field->bound.load(), static_cast<std::uint64_t>(sol.cost)));
      launch_field();
    }
    if (bidir && sol.cost >= 0)
      bidir->bound.store(std::min(bidir->bound.load(), static_cast<std::uint64_t>(sol.cost)));
    // Grids nobody will reuse need not go beyond the best path's cost.
    if (!g.config().cache.complete_grids && sol.cost >= 0)
      grids->stopBeyond(static_cast<std::uint64_t>(sol.cost));
    result.solutions.push_back(std::move(ls));
    if (on_solution) on_solution(result.solutions.back());
  };
  // The callback has put every solution into result.solutions; the summary is what is left.
  result.search = static_cast<const SearchSummary&>(planner->search(problem, remaining, cb));
  if (any_heading && !result.solutions.empty())
    result.planned_goal->theta = result.solutions.back().poses.back().theta;
  if (result.search.status == SearchStatus::kNoSolution && result.solutions.empty())
    describeNoPath(result.search, backward, problem.enclosedStates(), &result);
  if (escape) {
    result.escape_message =
        describeEscape(start_collision, *escape, start_options,
                       result.solutions.empty() ? nullptr : &result.solutions.back());
  }
  return result;
}

bool LatticePlanner::prepareKinematicTables(const SearchLimits& limits) const {
  const auto& tables = impl_->graph->kinematicTables();
  if (!tables) return true;
  const StopCondition stop = stopFor(limits);
  const LatticeConfig& c = impl_->graph->config();
  // A bidirectional proof's backward side measures from the start with the start's tables.
  if (!c.backward_search && c.heuristics.bidirectional_after_s >= 0.0 &&
      !tables->prepare(KinematicTables::Direction::kFromStart, &stop))
    return false;
  return tables->prepare(tableDirection(c.backward_search), &stop);
}

bool LatticePlanner::prepareKinematicTables(const Pose2D& start, const Pose2D& goal,
                                            const GoalOptions& goal_options,
                                            const SearchLimits& limits) const {
  const auto& tables = impl_->graph->kinematicTables();
  if (!tables) return true;
  const LatticeGraph& g = *impl_->graph;
  const bool backward = g.config().backward_search;
  int x = 0, y = 0, heading = 0;
  if (!g.poseToState(backward ? start : goal, &x, &y, &heading))
    return true;  // plan() will refuse it
  if (goal_options.any_heading && !backward) heading = kAnyHeading;
  const StopCondition stop = stopFor(limits);
  // A bidirectional proof's backward side measures from the start with the start's table.
  if (!backward && !goal_options.any_heading &&
      g.config().heuristics.bidirectional_after_s >= 0.0) {
    int sx = 0, sy = 0, sh = 0;
    if (g.poseToState(start, &sx, &sy, &sh) &&
        !tables->lookup(KinematicTables::Direction::kFromStart, sh, &stop).valid())
      return false;
  }
  return tables->lookup(tableDirection(backward), heading, &stop).valid();
}

std::size_t LatticePlanner::kinematicTableBytes() const {
  const auto& tables = impl_->graph->kinematicTables();
  return tables ? tables->bytes() : 0;
}

std::vector<std::array<double, 2>> LatticePlanner::footprintAt(const Pose2D& pose) const {
  return impl_->graph->footprint().at(pose);
}

PlannerConfig defaultPlannerConfig(Algorithm algorithm) {
  PlannerConfig c = defaultConfig(algorithm);
  if (algorithm == Algorithm::kAmhaStar) {
    c.w1 = 1.03;
    c.w2 = 5.0;
    c.weight_schedule = WeightSchedule::kCertified;
    c.certified_ratio = 0.0;
    c.certified_split = 0.0;
    c.publish_within_iterations = true;
    c.stall_expansions = 10000;
    c.stall_mid_w1 = 1.1;
    c.stall_mid_expansions = 5000;
    c.stall_w1 = 2.0;
    c.proof_anchor_only = true;
  }
  return c;
}

const LatticeGraph& LatticePlanner::graph() const { return *impl_->graph; }

const char* heuristicSourceName(HeuristicSource s) {
  switch (s) {
    case HeuristicSource::kNone:
      return "none";
    case HeuristicSource::kCached:
      return "cached";
    case HeuristicSource::kComputed:
      return "computed";
    case HeuristicSource::kRepaired:
      return "repaired";
  }
  return "unknown";
}

const char* noPathProofName(NoPathProof p) {
  switch (p) {
    case NoPathProof::kNone:
      return "none";
    case NoPathProof::kSearch:
      return "search";
    case NoPathProof::kStartEnclosed:
      return "start_enclosed";
    case NoPathProof::kGoalEnclosed:
      return "goal_enclosed";
  }
  return "unknown";
}

const char* queryErrorName(QueryError e) {
  switch (e) {
    case QueryError::kNone:
      return "none";
    case QueryError::kStartNotFinite:
      return "start_not_finite";
    case QueryError::kGoalNotFinite:
      return "goal_not_finite";
    case QueryError::kStartOutOfMap:
      return "start_out_of_map";
    case QueryError::kGoalOutOfMap:
      return "goal_out_of_map";
    case QueryError::kStartInCollision:
      return "start_in_collision";
    case QueryError::kGoalInCollision:
      return "goal_in_collision";
    case QueryError::kGoalUnreachable:
      return "goal_unreachable";
  }
  return "unknown";
}

}  // namespace lattice
}  // namespace amha
