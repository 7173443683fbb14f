// The planning server's maps (see planner_server.h): the latest valid map and the
// LatticePlanner built for it. Threads:
//  - the map subscription and its partial updates (<map topic>_updates) have their own callback
//    queue and thread, which checks each message and writes it into the current map;
//  - one builder thread (LatestJobRunner) builds the planner of the newest map; updates that
//    arrive during a build are folded into the next one, so the planner never falls behind a
//    fast costmap. Plans keep the planner they started on, and a request first waits for the
//    planner of every map and update received before it (waitForCurrentPlanner).
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include <geometry_msgs/TransformStamped.h>
#include <map_msgs/OccupancyGridUpdate.h>
#include <nav_msgs/OccupancyGrid.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <ros/spinner.h>

#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/ros/latest_job_runner.h"
#include "amha_planner/ros/planner_params.h"

namespace amha_planner {

class MapTracker {
 public:
  /// tf2's transform global frame <- `frame` at `stamp`, waiting up to `timeout` seconds for it;
  /// throws tf2::TransformException if there is none.
  using TransformToGlobal = std::function<geometry_msgs::TransformStamped(
      const std::string& frame, const ros::Time& stamp, double timeout)>;

  /// Subscribes to "map" under `nh` and to its updates, on its own callback queue (served from
  /// start()). The global frame and the map size cap are `startup`'s; the conversion, the robot
  /// and the memory cap are those `params` has in force. `after_build` runs on the builder
  /// thread after each build, before the kinematic tables are prepared.
  MapTracker(const ros::NodeHandle& nh, const PlannerParams& startup, ParamsInForce& params,
             TransformToGlobal to_global, std::function<void()> after_build);
  /// stop(), then the subscriptions are shut down.
  ~MapTracker();
  MapTracker(const MapTracker&) = delete;
  MapTracker& operator=(const MapTracker&) = delete;

  /// Starts taking maps and updates.
  void start();
  /// At shutdown: stops taking maps and updates, stops a build under way and drops one waiting,
  /// and wakes the requests waiting for a planner.
  void stop();

  /// The map topic, as resolved.
  std::string mapTopic() const { return map_sub_.getTopic(); }
  /// The latest valid map's planner (null before the first).
  std::shared_ptr<amha::lattice::LatticePlanner> currentPlanner() const;
  /// Why the last full map was refused while there was no planner (NO_MAP says it), else "".
  std::string refusedMapReason() const;

  /// Waits until the planner covers every map and update received so far. kCancelled if
  /// `cancel` or `shutting_down` is set first (a cancel wakes it at once if wakeWaiters() is
  /// called), kTimeUp if `deadline` passed first.
  enum class Wait { kReady, kCancelled, kTimeUp };
  Wait waitForCurrentPlanner(const std::atomic<bool>& cancel,
                             const std::atomic<bool>& shutting_down,
                             std::chrono::steady_clock::time_point deadline);
  /// Wakes the requests waiting in waitForCurrentPlanner (one of them was cancelled).
  void wakeWaiters();

  /// Puts `next` in force (with the map's lock held, so that a build takes a map and the
  /// parameters together) and, if `rebuild` and there is a map, has the builder rebuild the
  /// planner from the current map, which the requests from now on wait for. Returns whether
  /// there is a map.
  bool setParams(std::shared_ptr<const PlannerParams> next, bool rebuild);

 private:
  void onMap(const nav_msgs::OccupancyGrid::ConstPtr& msg);
  /// A map whose frame is not the global frame, with its origin transformed into the global
  /// frame by tf2 (waiting up to `tf_timeout` seconds; its header keeps the frame it came in,
  /// which its updates name); false with `why` set if there is no transform (then the map must
  /// be refused, not used as it is).
  bool mapInGlobalFrame(const nav_msgs::OccupancyGrid& in, double tf_timeout,
                        nav_msgs::OccupancyGrid* out, std::string* why);
  void onMapUpdate(const map_msgs::OccupancyGridUpdate::ConstPtr& update);
  /// What one build starts from: the maps and updates received since the last build.
  struct BuildInput {
    std::shared_ptr<const amha::lattice::GridMap> grid;  ///< the map to build (null: refused)
    /// The planner to build from (after updates alone), or null for a full build.
    std::shared_ptr<amha::lattice::LatticePlanner> previous;
    amha::lattice::CellRect changed;  ///< cells changed since previous's map
    std::uint64_t version = 0, updates = 0;
    bool full_map = false;
    std::uint32_t width = 0, height = 0;
    double resolution = 0.0;
    std::string error;                            ///< why the map was refused
    std::shared_ptr<const PlannerParams> params;  ///< the parameters to build with
    bool reconfigured = false;                    ///< built in full because the parameters changed
  };
  /// On the builder thread: builds the planner of the current map (with every update received
  /// so far) and makes it current; a map the lattice refuses is logged and the planner kept.
  /// After updates alone the new planner is built from the current one, recomputing only the
  /// part of it the updates can change.
  void rebuildPlanner();
  /// On the builder thread, after a build: the kinematic tables every later request needs.
  void prepareKinematicTables(const amha::lattice::LatticePlanner& planner);
  /// Takes what rebuildPlanner() is to build (map_mutex_), converting only changed cells.
  BuildInput takeUnbuiltMap();
  /// Makes `planner` current if there is one, and marks `version` built either way; without
  /// any planner, `map_error` (why a full map was refused) is what NO_MAP answers say.
  bool installPlanner(std::shared_ptr<amha::lattice::LatticePlanner> planner, std::uint64_t version,
                      const std::string& map_error);
  void logBuild(const BuildInput& in, double seconds, bool have_planner, bool incremental) const;

  const std::string global_frame_;
  const std::size_t max_map_cells_;
  ParamsInForce& params_;  ///< its lock is taken inside map_mutex_ when both are
  const TransformToGlobal to_global_;
  const std::function<void()> after_build_;

  ros::CallbackQueue map_queue_;
  std::unique_ptr<ros::AsyncSpinner> map_spinner_;
  ros::Subscriber map_sub_, map_updates_sub_;
  std::mutex map_mutex_;              ///< guards the eight below
  nav_msgs::OccupancyGrid last_map_;  ///< the latest accepted map, with its accepted updates
  /// The grid of the full map accepted since the last build started (as it came, without the
  /// updates after it), converted once when it was checked; null if none.
  std::shared_ptr<const amha::lattice::GridMap> unbuilt_grid_;
  std::uint64_t map_version_ = 0;         ///< maps and updates accepted into last_map_
  std::uint64_t unbuilt_updates_ = 0;     ///< updates accepted since the last build started
  amha::lattice::CellRect unbuilt_rect_;  ///< the cells they changed
  bool build_failed_ = false;             ///< the last build failed: the next one starts afresh
  /// The robot, motion model or map conversion changed: the next build converts last_map_
  /// again and builds in full.
  bool reconfigured_ = false;

  mutable std::mutex planner_mutex_;
  std::condition_variable planner_built_;  ///< signalled (planner_mutex_) after each build
  std::shared_ptr<amha::lattice::LatticePlanner> planner_;  ///< latest valid map's planner
  std::uint64_t built_version_ = 0;  ///< map_version_ of the last build (refused ones too)
  /// Why the last full map was refused while there was no planner (NO_MAP says it), else "".
  std::string refused_map_reason_;
  std::atomic<bool> stop_builds_{false};      ///< set at shutdown: a running build stops
  std::unique_ptr<LatestJobRunner> builder_;  ///< reset (joined) before the members it uses
};

}  // namespace amha_planner
