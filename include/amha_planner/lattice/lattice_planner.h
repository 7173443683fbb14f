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

#include "amha_planner/search/planner.h"

namespace amha {
namespace lattice {

/// Cell costs follow costmap_2d: 0 free .. 252 increasingly costly, 253 inscribed (the robot's
/// inscribed circle would touch an obstacle), 254 lethal (an obstacle), 255 unknown.
constexpr std::uint8_t kFreeCost = 0;
constexpr std::uint8_t kInscribedCost = 253;
constexpr std::uint8_t kLethalCost = 254;
constexpr std::uint8_t kUnknownCost = 255;

/// Cell sizes (metres) a map may have: much finer or coarser grids overflow the geometry's cell
/// units (a primitive or footprint in cells becomes infinite or NaN).
constexpr double kMinResolution = 1e-3;
constexpr double kMaxResolution = 1e3;
/// Largest |origin_x|, |origin_y| (metres; UTM coordinates fit): beyond it a double cannot
/// place a cell to a millimetre, and poses on the map would be wrong.
constexpr double kMaxOriginMagnitude = 1e8;
/// Largest |origin_yaw| (radians): beyond it a double holds an angle too coarsely for headings
/// (at 4e279 rad, every heading came out the same), and no real map is turned a million
/// radians (a quaternion gives [-pi, pi]).
constexpr double kMaxOriginYaw = 1e6;

/// Largest LatticeConfig::coarse_block: the abstraction's edges cost coarse_block^2 work per
/// action to build (about a second at 1024 with 16 headings).
constexpr int kMaxCoarseBlock = 1024;
/// Smallest turning radius (in cells of the map) the primitive generator is given: far below it an
/// arc degenerates (its curvature overflows), and every radius under a cell gives the same
/// primitives anyway (the tightest turn ends on a neighbouring cell).
constexpr double kMinTurningRadiusCells = 0.01;
/// Most cells the robot's footprint may sweep along all the primitives together, as bounded
/// before any is rasterised (each costs 16 bytes of precomputed offsets and ~0.5 us to
/// rasterise): 4.2 M cells, e.g. a robot of 1.5 m radius on 2.5 cm cells takes ~1.2 M. Larger
/// robots are refused (LatticeError kRobot) instead of taking minutes and gigabytes.
constexpr std::size_t kMaxSweptCells = std::size_t{1} << 22;

/// A 2-D map. Cell (0, 0) is the bottom-left cell (nav_msgs/OccupancyGrid order: row-major,
/// x fastest, row 0 at the origin); (origin_x, origin_y) is that cell's outer corner in the map
/// frame, and the grid is rotated by origin_yaw about it.
struct GridMap {
  int width = 0;
  int height = 0;
  double resolution = 0.0;  ///< metres per cell
  double origin_x = 0.0, origin_y = 0.0, origin_yaw = 0.0;
  std::vector<std::uint8_t> cost;  ///< width * height cell costs

  std::uint8_t at(int x, int y) const { return cost[static_cast<std::size_t>(y) * width + x]; }
};

/// How occupancy percentages (-1 unknown, 0..100) become cell costs.
struct OccupancyConversion {
  int lethal_threshold = 65;     ///< occupancy >= this: lethal (map_server's occupied_thresh 0.65)
  bool unknown_is_free = false;  ///< false: unknown cells are obstacles
};

/// Bad maps, primitive files or robot descriptions, with a message that names the problem.
class LatticeError : public std::runtime_error {
 public:
  enum class Kind { kMap, kPrimitives, kRobot, kConfig };
  LatticeError(Kind kind, const std::string& what) : std::runtime_error(what), kind_(kind) {}
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
};

/// The per-map work of a LatticePlanner constructed with limits (footprint sweeps, clearance,
/// openings, heuristic tables) was stopped by the cancel flag, the time budget or the memory
/// cap; status() says which (kCancelled, kTimeLimit, kMemoryLimit) and what() why.
class SetupStopped : public std::runtime_error {
 public:
  SetupStopped(SearchStatus status, const std::string& what) : std::runtime_error(what), status_(status) {}
  SearchStatus status() const { return status_; }

 private:
  SearchStatus status_;
};

/// Builds a GridMap from OccupancyGrid-style data. Throws LatticeError (kMap) for sizes that are
/// not positive, data whose length is not width * height, a resolution that is not positive
/// and finite or outside [kMinResolution, kMaxResolution], a non-finite origin or one farther
/// than kMaxOriginMagnitude, a yaw beyond kMaxOriginYaw, or a map larger than `max_cells`.
GridMap gridMapFromOccupancy(int width, int height, double resolution, double origin_x,
                             double origin_y, double origin_yaw, const std::int8_t* data,
                             std::size_t data_size, const OccupancyConversion& conversion,
                             std::size_t max_cells = std::size_t{1} << 26);

struct Pose2D {
  double x = 0.0, y = 0.0, theta = 0.0;
};

/// The cells [x0, x1) x [y0, y1) of a map (e.g. the part a costmap update changed).
struct CellRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x0 >= x1 || y0 >= y1; }
  /// The smallest rectangle holding both.
  CellRect unite(const CellRect& o) const {
    if (empty()) return o;
    if (o.empty()) return *this;
    return {std::min(x0, o.x0), std::min(y0, o.y0), std::max(x1, o.x1), std::max(y1, o.y1)};
  }
};

class LatticeGraph;
/// How the robot may move, for generated primitives (added after the API freeze): a
/// differential drive also turns on the spot, an Ackermann vehicle never does, an
/// omnidirectional robot also turns on the spot and slides sideways (Nav2's "diff", "ackermann"
/// and "omni").
enum class MotionModel { kDifferential, kAckermann, kOmni };

/// Which generator makes the primitives when no file is given (added after the API freeze).
enum class PrimitiveGenerator {
  kNearMinimal,  ///< a near-minimal control set (Pivtoraiko & Kelly; motion_primitives.h)
  kLegacy,       ///< the first generator: arcs to the neighbouring headings only
};

/// The robot and its motion model.
struct LatticeConfig {
  /// Primitive file, by extension: a Nav2 lattice file (.json) or an SBPL .mprim file (any
  /// other); empty: generate primitives from the options below.
  std::string mprim_file;
  int num_headings = 16;         ///< generated primitives: a multiple of 8
  double turning_radius = 0.5;   ///< generated primitives: minimum turning radius (m)
  bool allow_reverse = false;    ///< generated primitives: add backward motions
  bool turn_in_place = true;     ///< generated primitives: add turns on the spot
  std::vector<std::array<double, 2>> footprint;  ///< polygon (m, base frame); empty: a circle
  double robot_radius = 0.2;     ///< used when footprint is empty
  /// Edge cost = length x primitive multiplier x (1 + cost_penalty x worst cell cost / 252).
  /// Precisely (integers, kCostUnitsPerMetre units): base = round(ceil(kCostUnitsPerMetre x
  /// max(L, nominal_speed x |dtheta| / omega)) x multiplier), where L is the length of the
  /// primitive's intermediate-pose polyline, dtheta its heading change and omega =
  /// (pi / 4) / time_to_turn_45 (so turning in place is costed by time, as in SBPL); then
  /// cost = base + ceil(base x Q[c] / 65536) with Q[c] = ceil(65536 x cost_penalty x c / 252)
  /// and c the worst cost of the cells the robot's centre crosses. cost_penalty = 252 gives
  /// SBPL's cost x (c + 1). See docs/lattice.md.
  double cost_penalty = 1.0;
  /// Inadmissible heuristics (0..3): a Dijkstra for a point robot, then Dijkstras on maps with
  /// passages narrower than the inscribed / circumscribed diameter blocked (the paper's three).
  int num_inadmissible = 3;
  /// How the inadmissible heuristics are made (kinematic_table.h for the table):
  ///  - kKinematic: each is the larger of its Dijkstra and the anchor's kinematic table, as Nav2's
  ///    Smac combines its obstacle and distance heuristics; the point robot's Dijkstra is the
  ///    anchor's grid at full Euclidean scale (no extra Dijkstra);
  ///  - kPaper: the paper's 8-connected Dijkstras alone, at the Euclidean scale.
  enum class Inadmissible { kKinematic, kPaper };
  Inadmissible inadmissible = Inadmissible::kKinematic;

  // ---- Added after the API freeze (defaults keep the original behaviour). ----
  /// Robot speed (m/s) and the time to turn 45 degrees in place (s): SBPL's nominalvel and
  /// timetoturn45degsinplace (these defaults are sbpl_lattice_planner's). They only matter
  /// through the turning-time term of the edge cost above.
  double nominal_speed = 0.4;
  double time_to_turn_45 = 0.6;
  /// Anchor heuristic: true = max(Euclidean, an admissible cost-aware 8-connected grid
  /// Dijkstra whose step costs are scaled so it is a relaxation of the lattice); false = the
  /// Euclidean distance alone (the paper's anchor). Both are admissible and consistent.
  bool grid_anchor = true;
  /// Moves of the anchor's grid: 8 (the neighbours) or 16 (also the knight moves, whose
  /// directions are those of the usual 16-heading lattices: the grid's scale, and so its
  /// distances, then fall less short of the lattice's; see docs/lattice.md).
  int anchor_connectivity = 16;
  /// With grid_anchor: also take the exact cost-to-go on a block abstraction of the lattice
  /// (cells grouped into coarse_block x coarse_block blocks; 0 = automatic: at most ~250k
  /// abstract states, see coarse_lattice.h), which knows what turning costs. Admissible and
  /// consistent.
  bool coarse_anchor = true;
  int coarse_block = 0;
  /// With grid_anchor: also take the obstacle-free kinematic cost-to-go (the exact cost of the
  /// cheapest primitive sequence on an empty map, kinematic_table.h) within this radius of the
  /// goal, in metres (0: off). Admissible and consistent; the tables are built once per
  /// primitive set and shared by every query and map.
  double kinematic_radius = 15.0;
  /// The table covers at most this many cells of radius (20 m at 5 cm, 10 m at 2.5 cm).
  static constexpr int kMaxKinematicCells = 400;
  /// Add to the Euclidean and grid parts of the anchor a turning term: the cheapest cost of
  /// turning to the goal's heading (admissible and consistent either way). Off by default:
  /// under an inflation weight it draws the search towards states that face the goal's heading
  /// everywhere on the map, which on large maps with cheap turns costs up to 30x more
  /// expansions, and where turns are expensive (SBPL's cubicle: 20 s per 45 degrees) the block
  /// abstraction already knows their cost, so the term changes little there
  /// (docs/results/lattice.md, 1b).
  bool anchor_turn_term = false;
  /// Whether a weight w (ARA*'s epsilon, A-MHA*'s w1) inflates the heuristics' heading-aware
  /// terms too: the block abstraction, the kinematic table and the turning terms. Off (the
  /// default): the keys are g + h + (w - 1) b, with b the heading-blind part of h (the larger
  /// of the Euclidean and grid terms; an inadmissible heuristic's Dijkstra), so those terms
  /// count once (SearchProblem::hasInflationBases: every bound holds). Inflated, they reward
  /// turning early, by w times what the turn saves in h for once what it costs: with turns in
  /// place, weighted A* (epsilon = 3) on SBPL's Willow Garage map at 2.5 cm expands 507,737
  /// states for its first path with them inflated and 18,468 without
  /// (docs/results/lattice.md, 1.0). On: the paper's keys, g + w h.
  bool inflate_heading_terms = false;
  /// Search from the goal back to the start (as SBPL does by default). The heuristics are
  /// then computed from the start, so the cache helps only repeated queries from one start.
  bool backward_search = false;
  /// Goals whose heuristic grids are kept (each costs ~16 bytes per map cell).
  int heuristic_cache_size = 2;
  /// A planner built from the previous one after a map change keeps that one's cached grids
  /// and repairs them on the first query to their goal (HeuristicGridBuilder::repair: exact,
  /// and far quicker than computing them again unless the change reroutes most of the map).
  bool repair_heuristics = true;
  /// Generated primitives: the generator and the motion model (turn_in_place = false also keeps
  /// kDifferential and kOmni from turning on the spot). allow_reverse adds backward motions,
  /// costed reverse_multiplier times their forward twins; with a Nav2 file (.json, which has
  /// forward motions only) it adds them too, as Smac's allow_reverse_expansion does.
  PrimitiveGenerator primitive_generator = PrimitiveGenerator::kNearMinimal;
  MotionModel motion_model = MotionModel::kDifferential;
  double reverse_multiplier = 3.0;
};

/// A goal heading that any heading satisfies (GoalOptions::any_heading, and the heuristic
/// tables of such goals).
constexpr int kAnyHeading = -1;

/// What counts as reaching the goal (added after the API freeze; the defaults are the goal pose
/// exactly, as plan() without options).
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

/// What may happen when the start is in collision (added after the API freeze; the default
/// refuses such a start with kStartInCollision, as plan() without options).
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
  /// tolerance are all provably out of the start's reach (added after the API freeze).
  kGoalUnreachable,
};

/// Search costs are integers; this many units make one metre of free, straight driving.
constexpr double kCostUnitsPerMetre = 1000.0;

/// One improved solution on the lattice.
struct LatticeSolution {
  Solution search;            ///< ids, cost (units), bounds, timing, iteration, weights
  std::vector<Pose2D> poses;  ///< the path in the map frame, intermediate poses included
  /// search.elapsed_s plus the time this plan() call spent before the search: computing
  /// heuristic grids and, with a goal tolerance, choosing the goal (added after the API freeze).
  double elapsed_total_s = 0.0;
  /// With a start escape (PlanResult::start_escaped): poses[0 .. escape_poses) leave the
  /// start's collision, and poses[escape_poses - 1] is the path's first collision-free pose;
  /// escape_cost (units, in search.cost) is what those motions cost. 0 without an escape.
  std::size_t escape_poses = 0;
  Cost escape_cost = 0;
};

/// Where a query's heuristic grids came from.
enum class HeuristicSource {
  kCached,    ///< the cache (or another call computing them at the same time)
  kComputed,  ///< computed for this query
  kRepaired,  ///< repaired from the grids of the planner this one was built from
};

struct PlanResult {
  QueryError error = QueryError::kNone;
  /// Human-readable reason when error != kNone; when goal_substituted, what replaced the goal.
  std::string message;
  SearchResult search;        ///< status and every solution (state ids)
  std::vector<LatticeSolution> solutions;  ///< the same solutions, as poses
  /// Seconds this call spent computing the goal's heuristic grids, or waiting for another call
  /// computing them (0 when they were cached);
  /// it counts against limits.time_limit_s (added after the API freeze).
  double heuristic_seconds = 0.0;
  HeuristicSource heuristic_source = HeuristicSource::kCached;  ///< (added after the API freeze)
  /// The pose the search plans to: the centre of the goal's cell with the goal's heading bin
  /// or, when a goal tolerance replaced an obstructed goal, that substitute; with any heading,
  /// the heading of the last solution's end (if there is none, the goal's or a collision-free
  /// one). Set once it is known: always when error is kNone, unless a stop came while the
  /// substitute was chosen (added after the API freeze).
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
  /// escape motions from the start allowed). Set once the escape is found (added after the API
  /// freeze).
  bool start_escaped = false;
  /// How the last solution left the start's collision (empty without an escape).
  std::string escape_message;
  /// Seconds spent finding the escapes (they count against limits.time_limit_s too).
  double escape_seconds = 0.0;
};

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
  /// The same, honouring `limits` (added after the API freeze): its cancel flag and its time
  /// budget (counted from this call) stop the per-map work, and a per-map memory estimate
  /// above max_memory_bytes refuses it before it starts; each throws SetupStopped.
  /// max_expansions and max_states do not apply.
  LatticePlanner(std::shared_ptr<const GridMap> map, const LatticeConfig& config, const SearchLimits& limits);
  /// The planner of `map`, a version of previous.map() whose cells differ only inside
  /// `changed` (same size, resolution and origin; checked, else LatticeError): the same result
  /// as the constructor above with previous.config(), built from `previous` by recomputing only
  /// what the change can reach (the robot's primitives and footprint sweeps are copied, the
  /// clearance and openings recomputed near `changed`). previous's cached heuristic grids are
  /// kept and repaired on the first query to their goal (LatticeConfig::repair_heuristics).
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
  bool prepareKinematicTables(const Pose2D& start, const Pose2D& goal, const GoalOptions& goal_options,
                              const SearchLimits& limits = SearchLimits()) const;
  /// Bytes of the kinematic tables built so far (shared; 0 without tables).
  std::size_t kinematicTableBytes() const;
  /// The same with StartOptions (an escape from a start in collision): see there. The start
  /// tolerance must be finite and >= 0 and the penalty finite and >= 1, else
  /// std::invalid_argument.
  PlanResult plan(const Pose2D& start, const Pose2D& goal, const StartOptions& start_options,
                  const GoalOptions& goal_options, const PlannerConfig& algorithm, const SearchLimits& limits,
                  const std::function<void(const LatticeSolution&)>& on_solution = {});

  /// The footprint polygon placed at a pose (map frame), for drawing and markers.
  std::vector<std::array<double, 2>> footprintAt(const Pose2D& pose) const;

  /// The lattice it plans on: its map, primitives, footprint sweeps and edge costs (e.g. for
  /// PathSmoother, path_smoother.h). Lives as long as the planner (added after the API freeze).
  const LatticeGraph& graph() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The search configuration the lattice planner uses by default (CLI, server, benchmarks):
/// amha::defaultConfig(algorithm), except for A-MHA*, whose paper preset (w1 = w2 = 5, steps of
/// 0.5) gives a first path 10-15 % above the optimum and then nothing until the proof. Here it
/// starts at w1 = 1.1, w2 = 5 (with the kinematic inadmissible heuristics the first path is then
/// within about 1 % of the optimum), goes on with w1 = 2 if that first iteration has expanded
/// 10,000 states without a path (hard queries, where w1 = 1.1 crawls), then straight to the
/// proof (certified schedule, ratio 0: intermediate iterations cost more than they find,
/// docs/lattice.md), and publishes every cheaper path and every halving of the certified
/// bound's gap as the proof goes on.
PlannerConfig defaultPlannerConfig(Algorithm algorithm);

const char* queryErrorName(QueryError e);
const char* heuristicSourceName(HeuristicSource s);

}  // namespace lattice
}  // namespace amha
