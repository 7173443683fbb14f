// The lattice domain's base types: cell costs, maps, poses, cell rectangles and the errors
// of bad maps, primitives and robots. ROS-free; poses are in the map frame (REP 103).
#pragma once

#include <algorithm>
#include <cstdint>
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

/// Search costs are integers; this many units make one metre of free, straight driving.
constexpr double kCostUnitsPerMetre = 1000.0;

/// A goal heading that any heading satisfies (GoalOptions::any_heading, and the heuristic
/// tables of such goals).
constexpr int kAnyHeading = -1;

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

/// The status of work that `stop` stopped, as it said then: kCancelled, else kTimeLimit.
inline SearchStatus stoppedStatus(const StopCondition& stop) {
  return stop.stoppedBy() == StopReason::kCancelled ? SearchStatus::kCancelled
                                                    : SearchStatus::kTimeLimit;
}

/// The per-map work of a LatticePlanner constructed with limits (footprint sweeps, clearance,
/// openings, heuristic tables) was stopped by the cancel flag, the time budget or the memory
/// cap; status() says which (kCancelled, kTimeLimit, kMemoryLimit) and what() why.
class SetupStopped : public std::runtime_error {
 public:
  SetupStopped(SearchStatus status, const std::string& what)
      : std::runtime_error(what), status_(status) {}
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

}  // namespace lattice
}  // namespace amha
