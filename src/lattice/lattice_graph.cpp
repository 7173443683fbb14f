// Per-map precomputation of the lattice: actions, costs, clearance, openings, anchor scales.
#include "amha_planner/lattice/lattice_graph.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "amha_planner/lattice/detail/grid_moves.h"
#include "primitive_geometry.h"

namespace amha {
namespace lattice {

namespace {

[[noreturn]] void fail(LatticeError::Kind kind, const std::string& what) {
  throw LatticeError(kind, what);
}

std::string str(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

void validateMap(const GridMap& m) {
  const auto kind = LatticeError::Kind::kMap;
  if (m.width <= 0 || m.height <= 0)
    fail(kind, "map: size " + std::to_string(m.width) + " x " + std::to_string(m.height) +
                   " is not positive");
  if (m.cost.size() != static_cast<std::size_t>(m.width) * m.height)
    fail(kind, "map: cost array size does not match width x height");
  if (static_cast<std::size_t>(m.width) * m.height > (std::size_t{1} << 28))
    fail(kind, "map: more than 2^28 cells");
  if (!(m.resolution > 0.0) || !std::isfinite(m.resolution))
    fail(kind, "map: resolution " + str(m.resolution) + " is not positive");
  if (m.resolution < kMinResolution || m.resolution > kMaxResolution) {
    fail(kind, "map: resolution " + str(m.resolution) + " m is outside [" + str(kMinResolution) +
                   ", " + str(kMaxResolution) + "]");
  }
  if (!std::isfinite(m.origin_x) || !std::isfinite(m.origin_y) || !std::isfinite(m.origin_yaw))
    fail(kind, "map: origin is not finite");
  if (std::fabs(m.origin_x) > kMaxOriginMagnitude || std::fabs(m.origin_y) > kMaxOriginMagnitude) {
    fail(kind, "map: origin (" + str(m.origin_x) + ", " + str(m.origin_y) + ") is farther than " +
                   str(kMaxOriginMagnitude) + " m");
  }
  if (std::fabs(m.origin_yaw) > kMaxOriginYaw) {
    fail(kind, "map: origin yaw " + str(m.origin_yaw) + " rad is beyond +-" + str(kMaxOriginYaw) +
                   " rad");
  }
}

void validateConfig(const LatticeConfig& c, double resolution) {
  const auto kind = LatticeError::Kind::kConfig;
  if (c.motion.mprim_file.empty() &&
      !(c.motion.turning_radius >= kMinTurningRadiusCells * resolution &&
        std::isfinite(c.motion.turning_radius))) {
    fail(kind,
         "turning radius " + str(c.motion.turning_radius) + " m is below a hundredth of a cell (" +
             str(kMinTurningRadiusCells * resolution) + " m on this map of " + str(resolution) +
             " m cells) or not finite: the primitive generator cannot make a tighter arc, and any "
             "radius "
             "under a cell gives the same primitives (the tightest turn ends on a neighbouring "
             "cell)");
  }
  if (c.heuristics.coarse_block < 0 || c.heuristics.coarse_block > kMaxCoarseBlock) {
    fail(kind, "coarse_block " + std::to_string(c.heuristics.coarse_block) + " is not in 0.." +
                   std::to_string(kMaxCoarseBlock) + " (cells per block side; 0: automatic)");
  }
  if (c.heuristics.num_inadmissible < 0 || c.heuristics.num_inadmissible > 3)
    fail(kind,
         "num_inadmissible " + std::to_string(c.heuristics.num_inadmissible) + " is not in 0..3");
  if (!std::isfinite(c.cost.penalty) || c.cost.penalty < 0.0 || c.cost.penalty > 10000.0)
    fail(kind, "cost_penalty " + str(c.cost.penalty) + " is not in [0, 10000]");
  if (!(c.cost.nominal_speed > 0.0) || !std::isfinite(c.cost.nominal_speed))
    fail(kind, "nominal_speed " + str(c.cost.nominal_speed) + " must be positive");
  if (!(c.cost.time_to_turn_45 >= 0.0) || !std::isfinite(c.cost.time_to_turn_45))
    fail(kind, "time_to_turn_45 " + str(c.cost.time_to_turn_45) + " must not be negative");
  if (c.cache.size < 1) fail(kind, "heuristic_cache_size must be at least 1");
  if (c.heuristics.anchor_connectivity != 8 && c.heuristics.anchor_connectivity != 16) {
    fail(kind, "anchor_connectivity " + std::to_string(c.heuristics.anchor_connectivity) +
                   " is not 8 or 16");
  }
  if (!std::isfinite(c.heuristics.kinematic_radius) || c.heuristics.kinematic_radius < 0.0 ||
      c.heuristics.kinematic_radius > 100.0) {
    fail(kind, "kinematic_radius " + str(c.heuristics.kinematic_radius) + " m is not in [0, 100]");
  }
}

/// Bytes per map cell of the per-map data beyond the sweeps (clearance, openings, the distance
/// transforms' temporaries and the heuristic tables' levels), for the memory estimate.
constexpr std::size_t kSetupBytesPerCell = 16;
/// Bytes per swept cell: its linear offset and its (dx, dy).
constexpr std::size_t kBytesPerSweptCell = sizeof(std::int64_t) + sizeof(CellOffset);

}  // namespace

void throwIfStopped(const StopCondition* stop, const char* during) {
  if (stop == nullptr || !stop->requested()) return;
  const SearchStatus status = stoppedStatus(*stop);
  throw SetupStopped(
      status,
      std::string(status == SearchStatus::kCancelled ? "cancelled" : "time budget used up") +
          " while building the planner (" + during + ")");
}

LatticeGraph::LatticeGraph(std::shared_ptr<const GridMap> map, const LatticeConfig& config,
                           const GraphLimits& limits)
    : map_(std::move(map)), config_(config) {
  if (!map_) fail(LatticeError::Kind::kMap, "map: null");
  validateMap(*map_);
  validateConfig(config_, map_->resolution);
  primitives_ = primitivesFor(config_, map_->resolution);
  footprint_ = RobotFootprint::fromConfig(config_);
  checkRobotSize(limits);
  penalty_q_.resize(256);
  for (int c = 0; c < 256; ++c) {
    const double q = 65536.0 * config_.cost.penalty * std::min(c, 252) / 252.0;
    penalty_q_[c] = static_cast<std::int64_t>(std::ceil(q - 1e-9));
  }
  buildActions(limits.stop);
  throwIfStopped(limits.stop, "clearance and openings");
  computeClearanceAndOpenings(CellRect{0, 0, map_->width, map_->height});
  throwIfStopped(limits.stop, "clearance and openings");
  computeAnchorScales();
  if (config_.heuristics.grid_anchor && config_.heuristics.kinematic_radius > 0.0 &&
      euclid_per_cell_ > 0.0) {
    std::vector<KinematicMove> moves;
    moves.reserve(actions_.size());
    for (const LatticeAction& a : actions_)
      moves.push_back({a.dx, a.dy, a.start_heading, a.end_heading, a.base_cost});
    // At most kMaxKinematicCells: a table's size grows with the square of its radius in cells
    // (16 MB a table at 400 cells and 16 headings), and finer maps do not need a wider one.
    const int radius = std::min(
        LatticeConfig::kMaxKinematicCells,
        static_cast<int>(std::ceil(config_.heuristics.kinematic_radius / map_->resolution - 1e-9)));
    kinematic_ = KinematicTables::shared(moves, primitives_.heading_angles, euclid_per_cell_,
                                         std::max(1, radius));
  }
}

void LatticeGraph::checkRobotSize(const GraphLimits& limits) const {
  const GridMap& m = *map_;
  const double res = m.resolution;
  footprint_.checkFitsMap(m.width, m.height, res);
  // The cells a footprint sweeps lie within its circumscribed radius of the centre's path:
  // at most a disc plus a band along the path (cells: the radius grown by a cell's diagonal).
  double swept = 0.0;
  if (!footprint_.polygon.empty()) {
    const double r = footprint_.circumscribed_radius / res + 1.5;
    for (const MotionPrimitive& p : primitives_.primitives) {
      swept += M_PI * r * r + 2.0 * r * detail::polylineLength(p.poses) / res;
    }
  }
  if (swept > static_cast<double>(kMaxSweptCells)) {
    fail(LatticeError::Kind::kRobot,
         "robot footprint: sweeping it along the " + std::to_string(primitives_.primitives.size()) +
             " primitives would touch up to " + std::to_string(static_cast<long long>(swept)) +
             " cells (limit " + std::to_string(kMaxSweptCells) + "): its circumscribed radius of " +
             str(footprint_.circumscribed_radius) + " m is " +
             str(footprint_.circumscribed_radius / res) + " cells of " + str(res) +
             " m; use a coarser map or a smaller robot");
  }
  const double bytes =
      swept * kBytesPerSweptCell + static_cast<double>(m.cost.size()) * kSetupBytesPerCell;
  if (bytes > static_cast<double>(limits.max_bytes)) {
    throw SetupStopped(SearchStatus::kMemoryLimit,
                       "the planner's per-map data (footprint sweeps, clearance, openings, "
                       "heuristic tables) would "
                       "take about " +
                           str(std::ceil(bytes / 1e6)) + " MB, above the memory cap of " +
                           str(std::floor(static_cast<double>(limits.max_bytes) / 1e6)) + " MB");
  }
}

LatticeGraph::LatticeGraph(const LatticeGraph& previous, std::shared_ptr<const GridMap> map,
                           const CellRect& changed)
    : LatticeGraph(previous) {
  map_ = std::move(map);
  recomputed_ = CellRect{};
  if (!map_) fail(LatticeError::Kind::kMap, "map: null");
  validateMap(*map_);
  const GridMap& a = previous.map();
  const GridMap& b = *map_;
  // Actions hold linear offsets and the anchor scales metres per cell: both need the same grid.
  if (a.width != b.width || a.height != b.height || a.resolution != b.resolution ||
      a.origin_x != b.origin_x || a.origin_y != b.origin_y || a.origin_yaw != b.origin_yaw) {
    fail(LatticeError::Kind::kMap, "map update: the map's size, resolution or origin changed");
  }
  linkActionsInto();
  const CellRect inside{std::max(changed.x0, 0), std::max(changed.y0, 0),
                        std::min(changed.x1, b.width), std::min(changed.y1, b.height)};
  if (inside.empty()) return;
  // The values that can change: those within reach of a changed cell.
  const int m = dependenceMargin();
  computeClearanceAndOpenings(CellRect{std::max(inside.x0 - m, 0), std::max(inside.y0 - m, 0),
                                       std::min(inside.x1 + m, b.width),
                                       std::min(inside.y1 + m, b.height)});
}

int LatticeGraph::dependenceMargin() const {
  // A capped clearance depends on obstacles within the cap; an opening on obstacles within 2r
  // (the erosion reads r around each cell, the dilation r more). One cell more for rounding.
  double reach = clearance_cap_;
  if (config_.heuristics.num_inadmissible >= 2) {
    const std::array<double, 2> radii = openingRadii();
    reach = std::max({reach, 2.0 * radii[0], 2.0 * radii[1]});
  }
  return static_cast<int>(std::ceil(reach)) + 1;
}

void LatticeGraph::linkActionsInto() {
  actions_into_.assign(primitives_.num_headings, {});
  for (const LatticeAction& a : actions_) actions_into_[a.end_heading].push_back(&a);
}

void LatticeGraph::buildActions(const StopCondition* stop) {
  const double res = map_->resolution;
  const int n = primitives_.num_headings;
  const double omega =
      config_.cost.time_to_turn_45 > 0.0 ? (M_PI / 4.0) / config_.cost.time_to_turn_45 : 0.0;
  action_index_.assign(n + 1, 0);
  for (int h = 0; h < n; ++h) {
    action_index_[h] = actions_.size();
    const auto r = primitives_.range(h);
    for (std::size_t i = r.first; i < r.second; ++i) {
      throwIfStopped(stop, "footprint sweeps");
      const MotionPrimitive& p = primitives_.primitives[i];
      LatticeAction a;
      a.dx = p.end_dx;
      a.dy = p.end_dy;
      a.start_heading = p.start_heading;
      a.end_heading = p.end_heading;
      a.primitive = static_cast<int>(i);
      a.end_offset = static_cast<std::int64_t>(a.dy) * map_->width + a.dx;
      const double length = detail::polylineLength(p.poses);
      const double turn = angleDistance(primitives_.heading_angles[p.start_heading],
                                        primitives_.heading_angles[p.end_heading]);
      const double turn_as_distance = omega > 0.0 ? config_.cost.nominal_speed * turn / omega : 0.0;
      const double units =
          std::ceil(kCostUnitsPerMetre * std::max(length, turn_as_distance) - 1e-6);
      a.base_cost = std::max<Cost>(1, std::llround(units * p.cost_multiplier));

      PrimitiveCells cells = primitiveCells(footprint_, p.poses, res);
      a.min_dx = a.max_dx = a.min_dy = a.max_dy = 0;
      auto box = [&](const CellOffset& c) {
        a.min_dx = std::min(a.min_dx, c.dx);
        a.max_dx = std::max(a.max_dx, c.dx);
        a.min_dy = std::min(a.min_dy, c.dy);
        a.max_dy = std::max(a.max_dy, c.dy);
      };
      a.centre_begin = static_cast<std::uint32_t>(offsets_.size());
      for (const CellOffset& c : cells.centre) {
        box(c);
        offsets_.push_back(static_cast<std::int64_t>(c.dy) * map_->width + c.dx);
      }
      a.centre_end = static_cast<std::uint32_t>(offsets_.size());
      a.swept_begin = a.centre_end;
      double radius = 0.0;
      for (const CellOffset& c : cells.swept) {
        box(c);
        radius = std::max(radius, std::hypot(c.dx, c.dy));
        offsets_.push_back(static_cast<std::int64_t>(c.dy) * map_->width + c.dx);
      }
      a.swept_end = static_cast<std::uint32_t>(offsets_.size());
      // Rounded up so that "clearance > sweep_radius" really proves every swept cell free.
      a.sweep_radius = static_cast<float>(radius) * (1.0f + 1e-6f) + 1e-6f;
      actions_.push_back(a);
      action_cells_.push_back(std::move(cells));
    }
  }
  action_index_[n] = actions_.size();
  linkActionsInto();
  // Clearance only decides "clearance > sweep_radius": a cell keeps its class (clearance()).
  std::vector<float> sweeps;
  for (const LatticeAction& a : actions_) sweeps.push_back(a.sweep_radius);
  class_radii_ = clearanceClassRadii(std::move(sweeps));
  const auto& radii = class_radii_;
  for (LatticeAction& a : actions_) {
    // The smallest listed radius >= the action's own (its own, unless rounded up).
    a.sweep_class = static_cast<std::uint8_t>(
        std::lower_bound(radii.begin(), radii.end(), a.sweep_radius) - radii.begin());
  }
  clearance_cap_ = (radii.empty() ? 0.0f : radii.back()) + 1.0f;
  rest_cells_.resize(n);
  for (int h = 0; h < n; ++h) {
    if (!footprint_.polygon.empty()) {
      rest_cells_[h] =
          footprintCells(footprint_, Pose2D{0.0, 0.0, primitives_.heading_angles[h]}, res);
    }
  }
}

std::vector<float> clearanceClassRadii(std::vector<float> radii) {
  std::sort(radii.begin(), radii.end());
  radii.erase(std::unique(radii.begin(), radii.end()), radii.end());
  if (radii.size() > 255) {
    std::vector<float> levels(255);
    for (int k = 0; k < 255; ++k) levels[k] = radii.back() * static_cast<float>(k + 1) / 255.0f;
    levels.back() = radii.back();
    for (float& r : radii)
      r = *std::lower_bound(levels.begin(), levels.end(), r);  // the first >= r
    radii.erase(std::unique(radii.begin(), radii.end()), radii.end());
  }
  return radii;
}

std::array<double, 2> LatticeGraph::openingRadii() const {
  // A round robot's inscribed and circumscribed radii are both its radius (the polygon that
  // approximates the circle is only for the footprint cells).
  const bool round = config_.robot.footprint.empty();
  return {(round ? config_.robot.radius : footprint_.inscribed_radius) / map_->resolution,
          (round ? config_.robot.radius : footprint_.circumscribed_radius) / map_->resolution};
}

void LatticeGraph::computeClearanceAndOpenings(const CellRect& out) {
  recomputed_ = out;
  const int w = map_->width, h = map_->height;
  const std::size_t cells = static_cast<std::size_t>(w) * h;
  const bool openings = config_.heuristics.num_inadmissible >= 2;
  const std::array<double, 2> radii = openingRadii();
  // A point robot sweeps no cell and opens nothing: no distance transform, no clearance (a byte
  // a cell: 4 MB on a 2000 x 2000 map).
  const bool sweeps = std::any_of(actions_.begin(), actions_.end(), [](const LatticeAction& a) {
    return a.swept_end != a.swept_begin;
  });
  const bool opens = openings && (radii[0] > 0.0 || radii[1] > 0.0);
  // Reading the map dependenceMargin() around `out` gives every cell of `out` exactly the value
  // a whole-map computation gives it. Cells near the crop's edge may get wrong values (they do
  // not see obstacles beyond it), but they are more than r from `out`, too far to matter.
  const int margin = dependenceMargin();
  // Free space with a blocked border (padded coordinates: map cell (x, y) is (x + 1, y + 1)):
  // leaving the map is as bad as hitting a wall.
  const int cx0 = std::max(out.x0 + 1 - margin, 0), cy0 = std::max(out.y0 + 1 - margin, 0);
  const int cx1 = std::min(out.x1 + 1 + margin, w + 2), cy1 = std::min(out.y1 + 1 + margin, h + 2);
  const int cw = cx1 - cx0, ch = cy1 - cy0;
  cv::Mat dist;  // empty when neither the clearance nor an opening needs it
  if (sweeps || opens) {
    cv::Mat free(ch, cw, CV_8U, cv::Scalar(0));
    for (int py = std::max(cy0, 1); py < std::min(cy1, h + 1); ++py) {
      const int y = py - 1;
      const std::uint8_t* c = &map_->cost[static_cast<std::size_t>(y) * w];
      std::uint8_t* row = free.ptr<std::uint8_t>(py - cy0);
      for (int px = std::max(cx0, 1); px < std::min(cx1, w + 1); ++px) {
        row[px - cx0] = c[px - 1] < kLethalCost ? 255 : 0;
      }
    }
    cv::distanceTransform(free, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  }
  if (sweeps) clearance_.resize(cells);
  const float* class_radii = class_radii_.data();
  const int num_radii = static_cast<int>(class_radii_.size());
  const float top = num_radii > 0 ? class_radii[num_radii - 1] : 0.0f;
  for (int y = out.y0; sweeps && y < out.y1; ++y) {
    const float* d = dist.ptr<float>(y + 1 - cy0);  // d[x + 1 - cx0]: cell (x, y)
    std::uint8_t* c = clearance_.data() + static_cast<std::size_t>(y) * w;
    for (int x = out.x0; x < out.x1; ++x) {
      const float v = d[x + 1 - cx0];
      // Open space (beyond every radius) is the common case; else count the radii below v.
      c[x] = static_cast<std::uint8_t>(
          v > top ? num_radii
                  : std::lower_bound(class_radii, class_radii + num_radii, v) - class_radii);
    }
  }
  if (!openings) return;
  // Opening = dilation of the erosion: cells within r of a cell that is more than r from every
  // obstacle. Both steps are exact Euclidean distance transforms.
  // One mask for a round robot's one radius, none for a point: the heuristics' grids already
  // keep to cells below lethal (openedFree).
  openings_shared_ = radii[1] == radii[0];
  for (int k = 0; k < 2; ++k) {
    if (k == 1 && openings_shared_) break;
    const double r = radii[k];
    std::vector<std::uint8_t>& o = opened_[k];
    if (r <= 0.0) {
      o.clear();
      o.shrink_to_fit();
      continue;
    }
    o.resize(cells);
    cv::Mat not_eroded(ch, cw, CV_8U);
    for (int y = 0; y < ch; ++y) {
      const float* d = dist.ptr<float>(y);
      std::uint8_t* e = not_eroded.ptr<std::uint8_t>(y);
      for (int x = 0; x < cw; ++x) e[x] = d[x] > r ? 0 : 255;
    }
    cv::Mat d2;
    cv::distanceTransform(not_eroded, d2, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
    for (int y = out.y0; y < out.y1; ++y) {
      const float* d = d2.ptr<float>(y + 1 - cy0);
      const std::size_t row = static_cast<std::size_t>(y) * w;
      for (int x = out.x0; x < out.x1; ++x) {
        o[row + x] = d[x + 1 - cx0] <= r && map_->cost[row + x] < kLethalCost;
      }
    }
  }
  openings_equal_ = openings_shared_ || opened_[0] == opened_[1];
}

void LatticeGraph::computeAnchorScales() {
  // Euclidean anchor: every action moves its end cell by |d| cells and costs at least its base
  // cost, so h = floor(s |goal - cell|) with s <= base / |d| for every action is consistent:
  // h(p) - h(q) <= ceil(s |p - q|) <= base <= cost(p, q) (integers), and h(goal) = 0.
  //
  // Grid anchor: a valid action's centre cells are all passable for the anchor grid and no
  // costlier than its worst cell, so the grid has a walk from start to end cell inside them of
  // length w (walkLength); with grid steps scaled by k <= base / w for every action, every
  // lattice edge costs at least the grid distance between its ends times the same cell-cost
  // factor, so the grid distance is admissible and consistent. (A diagonal step of the walk
  // uses a side cell inside the centre cells; the grid charges the cheaper passable side,
  // which is no costlier, so the grid distance stays below the walk's cost.)
  //
  // Turning term: an action changes the heading by dtheta (radians), and the heading still to
  // change, |theta - theta_goal|, obeys the triangle inequality on the circle. Adding
  // b x |theta - theta_goal| keeps either anchor consistent if b x dtheta <= base - s |d| (resp.
  // base - k w) for every action: the cost of an edge then covers both terms' decrease.
  const std::vector<GridMove> moves = gridMoves(config_.heuristics.anchor_connectivity);
  const double inf = std::numeric_limits<double>::infinity();
  double euclid = inf, uniform = inf;
  std::vector<double> walks(actions_.size(), 0.0);
  for (std::size_t i = 0; i < actions_.size(); ++i) {
    const LatticeAction& a = actions_[i];
    if (a.dx == 0 && a.dy == 0) continue;
    const double base = static_cast<double>(a.base_cost);
    euclid = std::min(euclid, base / std::hypot(a.dx, a.dy));
    walks[i] = walkLength(action_cells_[i].centre, CellOffset{a.dx, a.dy}, moves);
    if (std::isfinite(walks[i]) && walks[i] > 0.0) uniform = std::min(uniform, base / walks[i]);
  }
  if (!std::isfinite(euclid)) euclid = 0.0;  // only turns in place: no distance information
  if (!std::isfinite(uniform)) uniform = 0.0;
  cheapest_per_cell_ = euclid;
  euclid_per_cell_ = euclid * (1.0 - 1e-9);
  // One scale per class of move (same length: the axis steps, the diagonals, the knight moves),
  // each as large as the actions allow, the short ones first: a uniform scale is held down by
  // the worst fit (Smac's 5 cm set: a turn to (7, 2), whose 16-connected walk is 1.4 % longer
  // than its arc) and then shortens moves that fit better, there the diagonals. The consistency
  // argument above holds for any move costs under which every action's centre cells contain a walk
  // no costlier than the action's base cost (walkLength with the scaled lengths).
  std::vector<double> scale(moves.size(), uniform);
  // The moves with their lengths times sc: walkLength then gives a walk's cost.
  auto scaledMoves = [&](const std::vector<double>& sc) {
    std::vector<GridMove> scaled = moves;
    for (std::size_t m = 0; m < moves.size(); ++m) scaled[m].length *= sc[m];
    return scaled;
  };
  auto fits = [&](const std::vector<double>& sc) {
    const std::vector<GridMove> scaled = scaledMoves(sc);
    for (std::size_t i = 0; i < actions_.size(); ++i) {
      if (!std::isfinite(walks[i]) || walks[i] <= 0.0) continue;
      const LatticeAction& a = actions_[i];
      const double w = walkLength(action_cells_[i].centre, CellOffset{a.dx, a.dy}, scaled);
      if (w > static_cast<double>(a.base_cost)) return false;
    }
    return true;
  };
  if (uniform > 0.0 && config_.heuristics.anchor_move_scales) {
    // Each class raised in turn from the uniform scale as far as the actions allow, the others
    // kept: the result is nowhere below the uniform grid. (Raising the axis steps by lowering
    // the knight moves instead, which Smac's set allows, cost more expansions than it saved.)
    std::vector<double> lengths;
    for (const GridMove& mv : moves) lengths.push_back(mv.length);
    std::sort(lengths.begin(), lengths.end());
    lengths.erase(std::unique(lengths.begin(), lengths.end()), lengths.end());
    for (const double len : lengths) {
      auto with = [&](double v) {
        std::vector<double> sc = scale;
        for (std::size_t m = 0; m < moves.size(); ++m)
          if (moves[m].length == len) sc[m] = v;
        return sc;
      };
      // No class above the cheapest cost per cell of displacement (the Euclidean scale).
      double lo = uniform, hi = euclid;
      if (fits(with(hi))) {
        lo = hi;
      } else if (fits(with(lo + (hi - lo) / 65536))) {  // else this class cannot rise
        for (int it = 0; it < 16; ++it) {
          const double mid = 0.5 * (lo + hi);
          (fits(with(mid)) ? lo : hi) = mid;
        }
      }
      scale = with(lo);
    }
  }
  grid_anchor_move_units_.clear();
  for (const double sc : scale) {
    grid_anchor_move_units_.push_back(sc * (1.0 - 1e-6));  // slack for the Q table's rounding
  }
  grid_anchor_per_cell_ = *std::min_element(scale.begin(), scale.end()) * (1.0 - 1e-6);
  const std::vector<GridMove> scaled = scaledMoves(grid_anchor_move_units_);
  double bt_e = inf, bt_g = inf;
  for (std::size_t i = 0; i < actions_.size(); ++i) {
    const LatticeAction& a = actions_[i];
    const MotionPrimitive& p = primitives_.primitives[a.primitive];
    const double turn = angleDistance(primitives_.heading_angles[p.start_heading],
                                      primitives_.heading_angles[a.end_heading]);
    if (turn <= 0.0) continue;
    const double base = static_cast<double>(a.base_cost);
    bt_e = std::min(bt_e, (base - euclid_per_cell_ * std::hypot(a.dx, a.dy)) / turn);
    const double w = std::isfinite(walks[i]) && walks[i] > 0.0
                         ? walkLength(action_cells_[i].centre, CellOffset{a.dx, a.dy}, scaled)
                         : 0.0;
    bt_g = std::min(bt_g, (base - w) / turn);
  }
  euclid_turn_per_rad_ = std::isfinite(bt_e) ? std::max(0.0, bt_e) * (1.0 - 1e-9) : 0.0;
  grid_turn_per_rad_ = std::isfinite(bt_g) ? std::max(0.0, bt_g) * (1.0 - 1e-6) : 0.0;
}

bool LatticeGraph::stateValid(int x, int y, int heading) const {
  const int w = map_->width, h = map_->height;
  if (x < 0 || y < 0 || x >= w || y >= h) return false;
  if (map_->at(x, y) >= kInscribedCost) return false;
  for (const CellOffset& c : rest_cells_[heading]) {
    const int cx = x + c.dx, cy = y + c.dy;
    if (cx < 0 || cy < 0 || cx >= w || cy >= h || map_->at(cx, cy) >= kLethalCost) return false;
  }
  return true;
}

bool LatticeGraph::poseToState(const Pose2D& pose, int* x, int* y, int* heading) const {
  const GridMap& m = *map_;
  const double c = std::cos(m.origin_yaw), s = std::sin(m.origin_yaw);
  const double dx = pose.x - m.origin_x, dy = pose.y - m.origin_y;
  const double gx = (c * dx + s * dy) / m.resolution, gy = (-s * dx + c * dy) / m.resolution;
  if (!(gx >= 0.0 && gy >= 0.0 && gx < m.width && gy < m.height)) return false;
  *x = static_cast<int>(gx);
  *y = static_cast<int>(gy);
  *heading = primitives_.headingIndex(pose.theta - m.origin_yaw);
  return true;
}

Pose2D LatticeGraph::cellPoseToMap(int x, int y, const Pose2D& rel) const {
  const GridMap& m = *map_;
  const double gx = (x + 0.5) * m.resolution + rel.x, gy = (y + 0.5) * m.resolution + rel.y;
  const double c = std::cos(m.origin_yaw), s = std::sin(m.origin_yaw);
  return {m.origin_x + c * gx - s * gy, m.origin_y + s * gx + c * gy,
          std::remainder(rel.theta + m.origin_yaw, 2.0 * M_PI)};
}

Pose2D LatticeGraph::stateToPose(int x, int y, int heading) const {
  return cellPoseToMap(x, y, Pose2D{0.0, 0.0, primitives_.heading_angles[heading]});
}

}  // namespace lattice
}  // namespace amha
