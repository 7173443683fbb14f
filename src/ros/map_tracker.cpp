// The planning server's maps (see map_tracker.h).
#include "amha_planner/ros/map_tracker.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include <tf2/exceptions.h>
#include <tf2_geometry_msgs/tf2_geometry_msgs.h>

#include "amha_planner/ros/conversions.h"

namespace amha_planner {

namespace lat = amha::lattice;

MapTracker::MapTracker(const ros::NodeHandle& nh, const PlannerParams& startup,
                       ParamsInForce& params, TransformToGlobal to_global,
                       std::function<void()> after_build)
    : global_frame_(startup.global_frame),
      max_map_cells_(startup.max_map_cells),
      params_(params),
      to_global_(std::move(to_global)),
      after_build_(std::move(after_build)) {
  builder_ = std::make_unique<LatestJobRunner>();
  ros::NodeHandle map_nh(nh);
  map_nh.setCallbackQueue(&map_queue_);
  map_sub_ = map_nh.subscribe("map", 1, &MapTracker::onMap, this);
  // Partial updates on "<map topic>_updates", as costmap_2d publishes them and rviz reads them.
  // Each one changes the map, so the queue is long: a dropped update would leave it wrong.
  map_updates_sub_ =
      map_nh.subscribe(map_sub_.getTopic() + "_updates", 100, &MapTracker::onMapUpdate, this);
  map_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &map_queue_);
}

MapTracker::~MapTracker() {
  stop();
  map_sub_.shutdown();
  map_updates_sub_.shutdown();
}

void MapTracker::start() { map_spinner_->start(); }

void MapTracker::stop() {
  map_spinner_->stop();
  stop_builds_ = true;
  builder_.reset();  // stops a build under way, drops one waiting
  planner_built_.notify_all();
}

std::shared_ptr<lat::LatticePlanner> MapTracker::currentPlanner() const {
  std::lock_guard<std::mutex> lock(planner_mutex_);
  return planner_;
}

bool MapTracker::setParams(std::shared_ptr<const PlannerParams> next, bool rebuild) {
  bool have_map = false;
  {
    std::lock_guard<std::mutex> lock(map_mutex_);
    params_.set(std::move(next));
    have_map = !last_map_.data.empty();
    if (rebuild && have_map) {
      reconfigured_ = true;
      ++map_version_;  // requests from now on wait for the planner built with them
    }
  }
  if (rebuild && have_map) builder_->post([this] { rebuildPlanner(); });
  return have_map;
}

bool MapTracker::mapInGlobalFrame(const nav_msgs::OccupancyGrid& in, double tf_timeout,
                                  nav_msgs::OccupancyGrid* out, std::string* why) {
  *out = in;
  const std::string frame = normaliseFrame(in.header.frame_id);
  if (frame.empty() || frame == global_frame_) return true;
  // The transform when the map was made (the latest one if it has no stamp): a map in a frame
  // that moves (odom) is placed where that frame was then.
  try {
    const auto t = to_global_(frame, in.header.stamp, tf_timeout);
    geometry_msgs::PoseStamped origin, moved;
    origin.header = in.header;
    origin.pose = in.info.origin;
    tf2::doTransform(origin, moved, t);
    out->info.origin = moved.pose;
  } catch (const tf2::TransformException& e) {
    *why = "it is in frame '" + frame + "', and there is no transform to the global frame '" +
           global_frame_ + "' (" + e.what() + ")";
    return false;
  }
  return true;
}

void MapTracker::onMap(const nav_msgs::OccupancyGrid::ConstPtr& msg) {
  // Checked (converted) here, so that a malformed map never replaces a good one; the planner
  // is built from this grid on the builder thread.
  std::shared_ptr<const lat::GridMap> grid;
  const std::shared_ptr<const PlannerParams> p = params_.get();
  nav_msgs::OccupancyGrid placed;
  std::string why;
  try {
    if (!mapInGlobalFrame(*msg, p->tf_timeout, &placed, &why)) throw std::runtime_error(why);
    grid = std::make_shared<const lat::GridMap>(
        gridMapFromOccupancy(placed, p->occupancy, max_map_cells_));
  } catch (const std::exception& e) {
    ROS_ERROR("amha_planner: map refused (%ux%u, resolution %g, %zu cells of data): %s; %s",
              msg->info.width, msg->info.height, msg->info.resolution, msg->data.size(), e.what(),
              currentPlanner() ? "keeping the previous map" : "no map yet, requests get NO_MAP");
    std::lock_guard<std::mutex> lock(planner_mutex_);
    refused_map_reason_ = e.what();
    return;
  }
  const std::string frame = normaliseFrame(msg->header.frame_id);
  if (!frame.empty() && frame != global_frame_) {
    ROS_INFO(
        "amha_planner: the map is in frame '%s': its origin, transformed into '%s', is (%.3f, "
        "%.3f)",
        msg->header.frame_id.c_str(), global_frame_.c_str(), placed.info.origin.position.x,
        placed.info.origin.position.y);
  }
  {
    std::lock_guard<std::mutex> lock(map_mutex_);
    // Its header keeps the frame it came in (updates name it); its origin is in the global frame.
    last_map_ = std::move(placed);
    ++map_version_;
    unbuilt_grid_ = std::move(grid);
    // Converted as the parameters said before a reconfiguration changed them: convert it again.
    const auto now = params_.get();
    if (now->occupancy.lethal_threshold != p->occupancy.lethal_threshold ||
        now->occupancy.unknown_is_free != p->occupancy.unknown_is_free) {
      reconfigured_ = true;
    }
    unbuilt_updates_ = 0;  // the updates before it are overwritten
    unbuilt_rect_ = lat::CellRect{};
  }
  builder_->post([this] { rebuildPlanner(); });
}

void MapTracker::onMapUpdate(const map_msgs::OccupancyGridUpdate::ConstPtr& update) {
  {
    std::lock_guard<std::mutex> lock(map_mutex_);
    if (last_map_.data.empty()) {
      ROS_WARN_THROTTLE(5.0,
                        "amha_planner: a map update on %s came before any valid map on %s: "
                        "ignored",
                        map_updates_sub_.getTopic().c_str(), map_sub_.getTopic().c_str());
      return;
    }
    // Checked before any cell is written: a refused update leaves the map as it was.
    try {
      applyOccupancyGridUpdate(*update, &last_map_);
    } catch (const std::exception& e) {
      ROS_ERROR("amha_planner: %s; keeping the current map", e.what());
      return;
    }
    ++map_version_;
    ++unbuilt_updates_;
    // applyOccupancyGridUpdate checked that the rectangle lies inside the map.
    const auto x = static_cast<int>(update->x), y = static_cast<int>(update->y);
    unbuilt_rect_ = unbuilt_rect_.unite(lat::CellRect{x, y, x + static_cast<int>(update->width),
                                                      y + static_cast<int>(update->height)});
  }
  builder_->post([this] { rebuildPlanner(); });
}

void MapTracker::rebuildPlanner() {
  const auto t0 = std::chrono::steady_clock::now();
  BuildInput in = takeUnbuiltMap();
  // Built off the locks: plans keep using the previous planner until the swap.
  std::shared_ptr<lat::LatticePlanner> planner;
  if (in.grid) {
    try {
      // A robot too large for the map, or per-map data beyond the memory cap, is refused
      // before the work (LatticeError, SetupStopped); shutdown stops a build under way.
      amha::SearchLimits limits;
      limits.cancel = &stop_builds_;
      limits.max_memory_bytes =
          static_cast<std::size_t>(in.params->max_memory_mb * 1024.0 * 1024.0);
      planner = in.previous
                    ? std::make_shared<lat::LatticePlanner>(*in.previous, in.grid, in.changed)
                    : std::make_shared<lat::LatticePlanner>(in.grid, in.params->lattice, limits);
    } catch (const std::exception& e) {
      in.error = e.what();
    }
  }
  const bool incremental = in.previous != nullptr;
  in.previous = nullptr;  // see installPlanner
  const std::shared_ptr<lat::LatticePlanner> built = planner;
  const bool have_planner =
      installPlanner(std::move(planner), in.version, in.full_map ? in.error : "");
  logBuild(in, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
           have_planner, incremental);
  // The replaced planner's arrays (megabytes per million cells) would otherwise stay resident.
  after_build_();
  if (built) prepareKinematicTables(*built);
}

void MapTracker::prepareKinematicTables(const lat::LatticePlanner& planner) {
  // The tables depend on the primitives and cost model only and are shared by every later
  // planner (kinematic_table.h), so this builds them once, after the first map, off the
  // requests' path; a request that comes first builds its own table and this waits for it.
  const std::size_t before = planner.kinematicTableBytes();
  const auto t0 = std::chrono::steady_clock::now();
  amha::SearchLimits limits;
  limits.cancel = &stop_builds_;
  const bool complete = planner.prepareKinematicTables(limits);
  const std::size_t after = planner.kinematicTableBytes();
  if (after != before || !complete) {
    ROS_INFO("amha_planner: kinematic tables %s in %.2f s, %.1f MB", complete ? "built" : "stopped",
             std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
             after / 1e6);
  }
}

MapTracker::BuildInput MapTracker::takeUnbuiltMap() {
  BuildInput in;
  // The current planner is the last build's (this thread makes them all): after updates alone
  // its map differs from the new one only in the updates' rectangle.
  in.previous = currentPlanner();
  std::lock_guard<std::mutex> lock(map_mutex_);
  in.params = params_.get();  // under map_mutex_, as a reconfiguration sets them with reconfigured_
  in.reconfigured = reconfigured_;
  reconfigured_ = false;
  in.version = map_version_;
  in.updates = unbuilt_updates_;
  in.changed = unbuilt_rect_;
  const std::shared_ptr<const lat::GridMap> full_grid = std::move(unbuilt_grid_);
  in.full_map = full_grid != nullptr;
  if (in.full_map || build_failed_ || in.reconfigured) in.previous = nullptr;
  unbuilt_updates_ = 0;
  unbuilt_grid_ = nullptr;
  unbuilt_rect_ = lat::CellRect{};
  in.width = last_map_.info.width;
  in.height = last_map_.info.height;
  in.resolution = last_map_.info.resolution;
  // `changed` is relative to the full map's grid, or else to the previous planner's map;
  // only its cells are converted again.
  const lat::GridMap* base = in.full_map   ? full_grid.get()
                             : in.previous ? &in.previous->map()
                                           : nullptr;
  try {
    if (in.reconfigured) {  // every cell again, with the new conversion
      in.grid = std::make_shared<const lat::GridMap>(
          gridMapFromOccupancy(last_map_, in.params->occupancy, max_map_cells_));
    } else if (in.full_map && in.changed.empty()) {
      in.grid = full_grid;
    } else if (base != nullptr) {
      auto patched = std::make_shared<lat::GridMap>(*base);
      convertOccupancyCells(last_map_, in.changed, in.params->occupancy, patched.get());
      in.grid = std::move(patched);
    } else {  // after a failed build: the current planner's map may be an older one
      in.grid = std::make_shared<const lat::GridMap>(
          gridMapFromOccupancy(last_map_, in.params->occupancy, max_map_cells_));
    }
  } catch (const std::exception& e) {
    in.error = e.what();
  }
  return in;
}

bool MapTracker::installPlanner(std::shared_ptr<lat::LatticePlanner> planner, std::uint64_t version,
                                const std::string& map_error) {
  {
    std::lock_guard<std::mutex> lock(map_mutex_);
    build_failed_ = !planner;
  }
  bool have_planner = false;
  std::shared_ptr<lat::LatticePlanner> replaced;
  {
    std::lock_guard<std::mutex> lock(planner_mutex_);
    if (planner) {
      replaced = std::move(planner_);
      planner_ = std::move(planner);
    }
    have_planner = planner_ != nullptr;
    built_version_ = version;  // a refused map counts as built: requests must not wait for it
    if (planner_ == nullptr && !map_error.empty()) refused_map_reason_ = map_error;
  }
  // Released before the waiting requests wake (unless a running plan still holds it): the new
  // planner then holds the heuristic grids it kept from it alone, and repairs them in place.
  replaced = nullptr;
  planner_built_.notify_all();
  return have_planner;
}

std::string MapTracker::refusedMapReason() const {
  std::lock_guard<std::mutex> lock(planner_mutex_);
  return refused_map_reason_;
}

void MapTracker::logBuild(const BuildInput& in, double seconds, bool have_planner,
                          bool incremental) const {
  // A reconfiguration of the robot or the map conversion rebuilds the current map in full.
  std::string what = in.full_map ? "map" : in.reconfigured ? "map (new parameters)" : "";
  if (in.updates > 0) {
    what += (in.full_map ? " + " : "") + std::to_string(in.updates) +
            (in.updates == 1 ? " update" : " updates (one build)");
  }
  if (!in.error.empty()) {
    const char* kept = have_planner ? "plans keep the previous planner" : "requests get NO_MAP";
    if (in.full_map || in.reconfigured) {
      ROS_ERROR("amha_planner: %s %ux%u refused: %s; %s", what.c_str(), in.width, in.height,
                in.error.c_str(), kept);
    } else {  // every update of a refused map would say the same
      ROS_ERROR_THROTTLE(5.0, "amha_planner: %s %ux%u refused: %s; %s", what.c_str(), in.width,
                         in.height, in.error.c_str(), kept);
    }
    return;
  }
  // Updates can come several times a second (costmap_2d): one line each only when debugging.
  ROS_LOG(in.full_map || in.reconfigured ? ros::console::levels::Info : ros::console::levels::Debug,
          ROSCONSOLE_DEFAULT_NAME,
          "amha_planner: %s %ux%u at %.3f m/cell accepted; lattice "
          "ready in %.2f s%s",
          what.c_str(), in.width, in.height, in.resolution, seconds,
          incremental ? " (rebuilt near the change only)" : "");
}

MapTracker::Wait MapTracker::waitForCurrentPlanner(const std::atomic<bool>& cancel,
                                                   const std::atomic<bool>& shutting_down,
                                                   std::chrono::steady_clock::time_point deadline) {
  std::uint64_t wanted = 0;
  {
    std::lock_guard<std::mutex> lock(map_mutex_);
    wanted = map_version_;
  }
  std::unique_lock<std::mutex> lock(planner_mutex_);
  while (built_version_ < wanted) {
    if (cancel || shutting_down) return Wait::kCancelled;
    if (std::chrono::steady_clock::now() >= deadline) return Wait::kTimeUp;
    // wakeWaiters() notifies under planner_mutex_, so a cancel wakes this at once; the timeout
    // only covers shutdown and the deadline.
    const auto poll = std::chrono::steady_clock::now() + std::chrono::milliseconds(50);
    planner_built_.wait_until(lock, std::min(deadline, poll));
  }
  return Wait::kReady;
}

void MapTracker::wakeWaiters() {
  std::lock_guard<std::mutex> wake(planner_mutex_);
  planner_built_.notify_all();
}

}  // namespace amha_planner
