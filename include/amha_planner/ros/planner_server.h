// The planning server behind both amha_planner/PlannerNodelet and planner_node: it keeps the
// latest valid map's LatticePlanner, answers ~plan, ~make_plan and ~plan_anytime by driving it,
// and streams every improved solution. Threads:
//  - the map subscription and its partial updates (<map topic>_updates) have their own callback
//    queue and thread, which checks each message and writes it into the current map;
//  - one builder thread (LatestJobRunner) builds the planner of the newest map; updates that
//    arrive during a build are folded into the next one, so the planner never falls behind a
//    fast costmap. Plans keep the planner they started on, and a request first waits for the
//    planner of every map and update received before it;
//  - the services have their own queue, served by max_queued_requests + 2 threads, each waiting
//    for its job's result;
//  - the action server's goal and cancel callbacks have their own queue and thread, so a cancel
//    reaches a running search at once;
//  - one worker thread (PlanQueue) runs the searches, one at a time;
//  - dynamic_reconfigure's ~set_parameters is served on the node's own queue: a change replaces
//    the parameters whole (requests take a snapshot when they start planning) and, for the robot,
//    motion model or map conversion, has the builder rebuild the planner from the current map.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>

#include <boost/thread/recursive_mutex.hpp>
#include <dynamic_reconfigure/server.h>
#include <map_msgs/OccupancyGridUpdate.h>
#include <nav_msgs/GetPlan.h>
#include <nav_msgs/OccupancyGrid.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <ros/spinner.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include "amha_planner/AmhaPlannerConfig.h"
#include "amha_planner/Plan.h"
#include "amha_planner/PlanAnytimeAction.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/ros/freed_memory.h"
#include "amha_planner/ros/latest_job_runner.h"
#include "amha_planner/ros/plan_anytime_server.h"
#include "amha_planner/ros/plan_queue.h"
#include "amha_planner/ros/planner_params.h"
#include "amha_planner/ros/request_conversion.h"

namespace amha_planner {

class PlannerServer {
 public:
  /// `nh` resolves the map topic; `pnh` (private) holds the parameters, services, action and
  /// published topics. Throws std::invalid_argument for bad parameters.
  PlannerServer(const ros::NodeHandle& nh, const ros::NodeHandle& pnh);
  ~PlannerServer();
  PlannerServer(const PlannerServer&) = delete;
  PlannerServer& operator=(const PlannerServer&) = delete;

 private:
  using ActionServer = PlanAnytimeServer;
  using GoalHandle = ActionServer::GoalHandle;
  /// Called with each improved solution's message while a request runs.
  using SolutionSink = std::function<void(const PlanSolution&)>;

  void onMap(const nav_msgs::OccupancyGrid::ConstPtr& msg);
  /// A map whose frame is not the global frame, with its origin transformed into the global
  /// frame by tf2 (waiting up to `tf_timeout` seconds; its header keeps the frame it came in,
  /// which its updates name); false with `why` set if there is no transform (then the map must
  /// be refused, not used as it is).
  bool mapInGlobalFrame(const nav_msgs::OccupancyGrid& in, double tf_timeout, nav_msgs::OccupancyGrid* out,
                        std::string* why);
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
    std::string error;  ///< why the map was refused
    std::shared_ptr<const PlannerParams> params;  ///< the parameters to build with
    bool reconfigured = false;  ///< built in full because the parameters changed
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
  /// Waits until the planner covers every map and update received so far. kCancelled if
  /// `cancel` or shutdown came first (a cancel wakes it at once: onCancel notifies),
  /// kTimeUp if `deadline` passed first.
  enum class MapWait { kReady, kCancelled, kTimeUp };
  MapWait waitForCurrentMap(const std::atomic<bool>& cancel, std::chrono::steady_clock::time_point deadline);
  bool onPlan(Plan::Request& req, Plan::Response& res);
  bool onMakePlan(nav_msgs::GetPlan::Request& req, nav_msgs::GetPlan::Response& res);
  void onGoal(GoalHandle goal);
  void onCancel(GoalHandle goal);
  /// Sends `res` as the goal's result, with the goal state its status calls for.
  void finishGoal(GoalHandle& goal, Plan::Response&& res);

  /// Queues `request` and waits for its response (BUSY when the queue is full).
  Plan::Response runBlocking(const PlannerRequest& request);
  /// A dynamic_reconfigure change: checked, then in force for the requests that start planning
  /// after it, rebuilding the planner if it must; refused (config reset, error logged) if bad.
  void onReconfigure(AmhaPlannerConfig& config, std::uint32_t level);
  /// The parameters in force (a snapshot: a reconfiguration replaces them whole).
  std::shared_ptr<const PlannerParams> params() const;
  /// Plans one request on the worker thread; `cancel` stops it.
  Plan::Response execute(const PlannerRequest& request, std::uint32_t id,
                         const std::atomic<bool>& cancel, const SolutionSink& sink);
  /// Resolves a request pose into the global frame (tf2); false with status and message set.
  /// Throws TransformCancelled if `cancel` is set while it waits for a transform.
  bool toGlobalFrame(const geometry_msgs::PoseStamped& in, bool is_start, double tf_timeout,
                     geometry_msgs::PoseStamped* out, Plan::Response* res, const std::atomic<bool>& cancel);
  struct TransformCancelled {};
  /// tf2's transform target <- source at `time`, waiting up to `timeout` seconds for it; throws
  /// tf2::TransformException if there is none, TransformCancelled if `cancel` (may be null) is
  /// set while it waits.
  geometry_msgs::TransformStamped lookupTransform(const std::string& target, const std::string& source,
                                                  const ros::Time& time, double timeout,
                                                  const std::atomic<bool>* cancel);

  std::shared_ptr<amha::lattice::LatticePlanner> currentPlanner() const;
  /// After a build or a request: returns freed heap to the system once much has been freed
  /// (a 4000 x 4000 map's planner frees tens of MB that glibc would otherwise keep).
  void releaseFreedMemory();
  std::shared_ptr<std::atomic<bool>> newCancelFlag();
  void releaseCancelFlag(const std::shared_ptr<std::atomic<bool>>& flag);

  ros::NodeHandle nh_, pnh_;
  /// The parameters read at start-up. Those dynamic_reconfigure cannot change (frames, queue
  /// length, map size cap, release_freed_memory) are read from here, without a lock.
  const PlannerParams startup_;
  mutable std::mutex params_mutex_;  ///< guards params_ (taken inside map_mutex_ when both are)
  std::shared_ptr<const PlannerParams> params_;

  ros::CallbackQueue map_queue_, service_queue_, action_queue_;
  std::unique_ptr<ros::AsyncSpinner> map_spinner_, service_spinner_, action_spinner_;
  ros::Subscriber map_sub_, map_updates_sub_;
  std::mutex map_mutex_;  ///< guards the eight below
  nav_msgs::OccupancyGrid last_map_;  ///< the latest accepted map, with its accepted updates
  /// The grid of the full map accepted since the last build started (as it came, without the
  /// updates after it), converted once when it was checked; null if none.
  std::shared_ptr<const amha::lattice::GridMap> unbuilt_grid_;
  std::uint64_t map_version_ = 0;     ///< maps and updates accepted into last_map_
  std::uint64_t unbuilt_updates_ = 0; ///< updates accepted since the last build started
  amha::lattice::CellRect unbuilt_rect_;  ///< the cells they changed
  bool build_failed_ = false;         ///< the last build failed: the next one starts afresh
  /// The robot, motion model or map conversion changed: the next build converts last_map_
  /// again and builds in full.
  bool reconfigured_ = false;
  ros::ServiceServer plan_srv_, make_plan_srv_;
  ros::Publisher solutions_pub_, path_pub_, markers_pub_;
  std::unique_ptr<ActionServer> action_server_;

  tf2_ros::Buffer tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;

  mutable std::mutex planner_mutex_;
  std::condition_variable planner_built_;  ///< signalled (planner_mutex_) after each build
  std::shared_ptr<amha::lattice::LatticePlanner> planner_;  ///< latest valid map's planner
  std::uint64_t built_version_ = 0;  ///< map_version_ of the last build (refused ones too)
  /// Why the last full map was refused while there was no planner (NO_MAP says it), else "".
  std::string refused_map_reason_;
  std::atomic<bool> stop_builds_{false};  ///< set at shutdown: a running build stops
  std::unique_ptr<LatestJobRunner> builder_;  ///< reset (joined) before the members it uses

  std::atomic<std::uint32_t> next_request_id_{1};
  std::atomic<bool> shutting_down_{false};
  std::mutex flags_mutex_;
  std::set<std::shared_ptr<std::atomic<bool>>> cancel_flags_;  ///< of queued/running requests

  /// An accepted action goal: its cancel flag and whether its job has started. A goal
  /// cancelled while it waits in the queue is answered at once by onCancel, and its job then
  /// does nothing (the queue may be busy for a whole time budget).
  struct GoalJob {
    std::shared_ptr<std::atomic<bool>> cancel;
    std::uint32_t request_id = 0;
    std::uint64_t ticket = 0;  ///< its place in queue_
    enum Phase : int { kQueued, kRunning, kDone };
    std::atomic<int> phase{kQueued};
  };
  std::mutex goals_mutex_;  ///< also orders setAccepted before the job's first step
  std::map<std::string, std::shared_ptr<GoalJob>> goal_jobs_;

  FreedMemoryReleaser freed_memory_{std::size_t{32} << 20};

  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<AmhaPlannerConfig>> reconfigure_;

  std::unique_ptr<PlanQueue> queue_;  ///< last member: destroyed (joined) first
};

}  // namespace amha_planner
