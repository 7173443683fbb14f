// The (x, y, theta) lattice on one map for one robot: primitives turned into actions with their
// cells as linear offsets, integer edge costs, collision checks and pose <-> state conversion.
// Immutable after construction, so any number of searches may share it.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "amha_planner/lattice/detail/footprint.h"
#include "amha_planner/lattice/detail/kinematic_table.h"
#include "amha_planner/lattice/lattice_config.h"
#include "amha_planner/lattice/motion_primitives.h"
#include "amha_planner/search/stop_condition.h"

namespace amha {
namespace lattice {

/// A primitive ready for the search.
struct LatticeAction {
  int dx = 0, dy = 0;  ///< end cell relative to the start cell
  int start_heading = 0;
  int end_heading = 0;
  int primitive = 0;            ///< index into PrimitiveSet::primitives
  Cost base_cost = 1;           ///< cost on free cells (see LatticeConfig::CostModel::penalty)
  std::int64_t end_offset = 0;  ///< dy * width + dx
  int min_dx = 0, max_dx = 0, min_dy = 0, max_dy = 0;  ///< box of every cell it touches
  /// Largest distance (cells) from the start cell to a swept cell: if the start cell is
  /// farther than this from every lethal cell, no swept cell can be lethal.
  float sweep_radius = 0.0f;
  /// Its rank among the distinct sweep radii: the start cell's clearance class exceeds it
  /// exactly when the cell's clearance exceeds sweep_radius (LatticeGraph::clearance()).
  std::uint8_t sweep_class = 0;
  std::uint32_t centre_begin = 0, centre_end = 0;  ///< into LatticeGraph::offsets()
  std::uint32_t swept_begin = 0, swept_end = 0;
};

constexpr Cost kInvalidEdge = -1;

/// What may stop a graph's construction (LatticePlanner's constructor with limits).
struct GraphLimits {
  /// Its cancel flag and deadline stop the work between steps (SetupStopped); null: never.
  const StopCondition* stop = nullptr;
  /// Refuses (SetupStopped, kMemoryLimit) a graph whose per-map data are estimated above this.
  std::size_t max_bytes = std::numeric_limits<std::size_t>::max();
};

/// Throws SetupStopped (kCancelled or kTimeLimit) if `stop` (may be null) asks to stop;
/// `during` names the step for the message.
void throwIfStopped(const StopCondition* stop, const char* during);

/// The radii that bound the clearance classes, for actions with these sweep radii: the distinct
/// ones, ascending; more than 255 are rounded up onto 255 levels (a larger radius only sends the
/// search to the full footprint check more often), so that a class fits in a byte.
std::vector<float> clearanceClassRadii(std::vector<float> sweep_radii);

class LatticeGraph {
 public:
  /// Loads/generates primitives, validates them against the map, precomputes every action's
  /// cells and costs, the clearance map, and the free-space openings for the heuristics.
  /// Throws LatticeError, or SetupStopped when `limits` stop it.
  LatticeGraph(std::shared_ptr<const GridMap> map, const LatticeConfig& config,
               const GraphLimits& limits = GraphLimits());
  /// The graph of `map`, whose cells differ from previous.map()'s only inside `changed` (same
  /// size, resolution and origin, else LatticeError): equal to LatticeGraph(map,
  /// previous.config()), but the actions are copied and only the clearance and openings that
  /// the change can reach are recomputed.
  LatticeGraph(const LatticeGraph& previous, std::shared_ptr<const GridMap> map,
               const CellRect& changed);
  LatticeGraph& operator=(const LatticeGraph&) = delete;

  const GridMap& map() const { return *map_; }
  const LatticeConfig& config() const { return config_; }
  const PrimitiveSet& primitives() const { return primitives_; }
  const RobotFootprint& footprint() const { return footprint_; }
  int width() const { return map_->width; }
  int height() const { return map_->height; }
  int numHeadings() const { return primitives_.num_headings; }

  const LatticeAction* actionsBegin(int heading) const {
    return actions_.data() + action_index_[heading];
  }
  const LatticeAction* actionsEnd(int heading) const {
    return actions_.data() + action_index_[heading + 1];
  }
  const std::vector<LatticeAction>& actions() const { return actions_; }
  /// `a`'s index in actions() (the label of its search edges).
  std::uint32_t actionIndex(const LatticeAction* a) const {
    return static_cast<std::uint32_t>(a - actions_.data());
  }
  /// Actions ending in `heading` (for backward search).
  const std::vector<const LatticeAction*>& actionsInto(int heading) const {
    return actions_into_[heading];
  }
  const std::vector<std::int64_t>& offsets() const { return offsets_; }
  /// Cell offsets (not linearised) of an action's centre and swept cells, for tools and tests.
  const PrimitiveCells& actionCells(std::size_t action) const { return action_cells_[action]; }

  /// Cost of taking `a` from cell (x, y), or kInvalidEdge if it leaves the map, its centre
  /// crosses an inscribed/lethal/unknown cell, or its footprint sweeps a lethal/unknown cell.
  Cost edgeCost(int x, int y, const LatticeAction& a) const {
    if (x + a.min_dx < 0 || x + a.max_dx >= map_->width || y + a.min_dy < 0 ||
        y + a.max_dy >= map_->height) {
      return kInvalidEdge;
    }
    const std::int64_t base = static_cast<std::int64_t>(y) * map_->width + x;
    const std::uint8_t* cost = map_->cost.data() + base;
    unsigned worst = 0;
    for (std::uint32_t k = a.centre_begin; k < a.centre_end; ++k) {
      const unsigned c = cost[offsets_[k]];
      if (c >= kInscribedCost) return kInvalidEdge;
      worst = c > worst ? c : worst;
    }
    // No swept cells (a point robot): no clearance kept, nothing to test.
    if (a.swept_end != a.swept_begin && clearance_[base] <= a.sweep_class) {
      for (std::uint32_t k = a.swept_begin; k < a.swept_end; ++k) {
        if (cost[offsets_[k]] >= kLethalCost) return kInvalidEdge;
      }
    }
    return a.base_cost + ((a.base_cost * penalty_q_[worst] + 65535) >> 16);
  }
  /// The edge cost formula alone (for validators): base cost and the worst centre-cell cost.
  Cost costWithPenalty(Cost base_cost, unsigned worst_cell_cost) const {
    return base_cost + ((base_cost * penalty_q_[worst_cell_cost] + 65535) >> 16);
  }

  /// The robot at rest at (x, y, heading): inside the map, centre cell below inscribed, no
  /// lethal/unknown cell under the footprint.
  bool stateValid(int x, int y, int heading) const;

  /// Map-frame pose -> lattice state (cell containing the point, nearest heading). Returns
  /// false if the point is outside the map.
  bool poseToState(const Pose2D& pose, int* x, int* y, int* heading) const;
  /// Centre of cell (x, y) with heading `heading`, in the map frame.
  Pose2D stateToPose(int x, int y, int heading) const;
  /// A pose relative to cell (x, y)'s centre (grid frame) -> map frame.
  Pose2D cellPoseToMap(int x, int y, const Pose2D& relative) const;

  /// Anchor scales (cost units per cell of distance): Euclidean, and the grid relaxation's
  /// smallest over its moves (the one scale of every move without anchor_move_scales).
  double euclidUnitsPerCell() const { return euclid_per_cell_; }
  double gridAnchorUnitsPerCell() const { return grid_anchor_per_cell_; }
  /// The grid relaxation's scale per move of gridMoves(anchor_connectivity), in that order.
  const std::vector<double>& gridAnchorMoveUnits() const { return grid_anchor_move_units_; }
  double cheapestUnitsPerCell() const { return cheapest_per_cell_; }
  /// Turning terms (cost units per radian of heading still to change) that may be added to the
  /// Euclidean / grid anchor without losing consistency (see computeAnchorScales).
  double euclidTurnUnitsPerRadian() const { return euclid_turn_per_rad_; }
  double gridTurnUnitsPerRadian() const { return grid_turn_per_rad_; }

  /// The obstacle-free kinematic tables of this graph's actions (null when
  /// LatticeConfig::Heuristics::kinematic_radius is 0 or the anchor is the Euclidean one): shared
  /// with every graph that has the same actions, whatever its map.
  const std::shared_ptr<KinematicTables>& kinematicTables() const { return kinematic_; }

  /// Per cell, its clearance class: how many of the distinct sweep radii (ascending) the
  /// distance from its centre to the nearest lethal/unknown cell centre exceeds. The search
  /// asks only "clearance > sweep radius", which a byte answers as well as the distance (a
  /// quarter of a float's memory, and of what an incremental build copies). Empty when no
  /// action sweeps a cell beyond its centre cells (a point robot, e.g. on an inflated costmap):
  /// then nothing asks.
  const std::vector<std::uint8_t>& clearance() const { return clearance_; }
  /// The distinct sweep radii (cells, ascending) that bound the classes: a cell's class exceeds
  /// k exactly when its clearance exceeds clearanceRadii()[k] (e.g. for PathSmoother, which
  /// skips the footprint test where the clearance proves it free, as edgeCost does).
  const std::vector<float>& clearanceRadii() const { return class_radii_; }
  /// Distances at or beyond this (cells) are all in the top class: a change farther away
  /// cannot alter a cell's class.
  float clearanceCap() const { return clearance_cap_; }
  /// The cells whose clearance and openings this graph computed: all of them, or for a graph
  /// built from a previous one, those the change could reach (the rest are the previous
  /// graph's; they and the map's costs are equal there).
  const CellRect& recomputed() const { return recomputed_; }
  /// Free space (1) opened by the inscribed (index 0) / circumscribed (index 1) radius, or
  /// nullptr when that radius is 0 (a point robot: every cell below lethal, no mask to keep).
  /// A round robot's two radii are one: both indices give the same mask.
  const std::vector<std::uint8_t>* openedFree(int which) const {
    const std::vector<std::uint8_t>& o = opened_[which == 1 && openings_shared_ ? 0 : which];
    return o.empty() ? nullptr : &o;
  }
  /// True when the two openings are the same cells (then the heuristics share one grid).
  bool openingsEqual() const { return openings_equal_; }

 private:
  /// Member-wise, for the incremental constructor only (actionsInto() must then be relinked:
  /// it points into the copied-from graph's actions).
  LatticeGraph(const LatticeGraph&) = default;
  /// Refuses robots that fit nowhere on the map or whose sweeps would be too large, and
  /// estimates the per-map bytes against `limits` (before any sweep is computed).
  void checkRobotSize(const GraphLimits& limits) const;
  void buildActions(const StopCondition* stop);
  void linkActionsInto();
  /// The radii (cells) of the two openings.
  std::array<double, 2> openingRadii() const;
  /// How far (cells) a cell's clearance or opening can depend on other cells' costs.
  int dependenceMargin() const;
  /// Computes clearance_ and opened_ on the cells of `out` (all of them on first use), reading
  /// the map only as far around `out` as their values can depend on.
  void computeClearanceAndOpenings(const CellRect& out);
  void computeAnchorScales();

  std::shared_ptr<const GridMap> map_;
  LatticeConfig config_;
  PrimitiveSet primitives_;
  RobotFootprint footprint_;
  std::vector<LatticeAction> actions_;
  std::vector<std::size_t> action_index_;  // numHeadings() + 1 entries
  std::vector<std::vector<const LatticeAction*>> actions_into_;
  std::vector<PrimitiveCells> action_cells_;
  std::vector<std::int64_t> offsets_;
  std::vector<std::vector<CellOffset>> rest_cells_;  // footprint at rest, per heading
  std::vector<std::int64_t> penalty_q_;              // 256 entries: Q[c]
  std::vector<std::uint8_t> clearance_;              // empty unless some action sweeps a cell
  std::vector<float> class_radii_;  // the distinct sweep radii, ascending (at most 255)
  float clearance_cap_ = 0.0f;
  CellRect recomputed_;
  std::vector<std::uint8_t> opened_[2];  // empty: radius 0, no mask (openedFree)
  bool openings_shared_ = false;         // equal radii: opened_[1] is not kept
  bool openings_equal_ = false;
  double euclid_per_cell_ = 0.0, grid_anchor_per_cell_ = 0.0, cheapest_per_cell_ = 0.0;
  std::vector<double> grid_anchor_move_units_;
  double euclid_turn_per_rad_ = 0.0, grid_turn_per_rad_ = 0.0;
  std::shared_ptr<KinematicTables> kinematic_;
};

}  // namespace lattice
}  // namespace amha
