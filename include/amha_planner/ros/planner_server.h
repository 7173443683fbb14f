// The planning server behind both amha_planner/PlannerNodelet and planner_node: it keeps the
// latest valid map's LatticePlanner, answers ~plan, ~make_plan and ~plan_anytime by driving it,
// and streams every improved solution. Threads:
//  - the map, its partial updates and the builds of its planner have MapTracker's threads (see
//    map_tracker.h); a request first waits for the planner of every map and update received
//    before it;
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
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include <dynamic_reconfigure/server.h>
#include <nav_msgs/GetPlan.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <ros/spinner.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <boost/thread/recursive_mutex.hpp>

#include "amha_planner/AmhaPlannerConfig.h"
#include "amha_planner/Plan.h"
#include "amha_planner/PlanAnytimeAction.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/ros/freed_memory.h"
#include "amha_planner/ros/map_tracker.h"
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
  /// execute()'s search: plans `query` from `start` to `goal` on `planner` within `limits`,
  /// publishing each improved solution as it is found (~solutions, ~plan, ~footprints and
  /// `sink`), smoothed with ~smooth_path, and adding its message to res->solutions (res holds
  /// the request's id and its path's stamp); *best_poses receives the poses of the path
  /// published last.
  amha::lattice::PlanResult search(amha::lattice::LatticePlanner& planner,
                                   const PlannerParams& params, const PlanQuery& query,
                                   const amha::lattice::Pose2D& start,
                                   const amha::lattice::Pose2D& goal,
                                   const amha::SearchLimits& limits, const SolutionSink& sink,
                                   Plan::Response* res,
                                   std::vector<amha::lattice::Pose2D>* best_poses);
  /// Resolves a request pose into the global frame (tf2); false with status and message set.
  /// Throws TransformCancelled if `cancel` is set while it waits for a transform.
  bool toGlobalFrame(const geometry_msgs::PoseStamped& in, bool is_start, double tf_timeout,
                     geometry_msgs::PoseStamped* out, Plan::Response* res,
                     const std::atomic<bool>& cancel);
  struct TransformCancelled {};
  /// tf2's transform target <- source at `time`, waiting up to `timeout` seconds for it; throws
  /// tf2::TransformException if there is none, TransformCancelled if `cancel` (may be null) is
  /// set while it waits.
  geometry_msgs::TransformStamped lookupTransform(const std::string& target,
                                                  const std::string& source, const ros::Time& time,
                                                  double timeout, const std::atomic<bool>* cancel);

  /// The constructor's steps after the queue: the map tracker, services, action, spinners and
  /// reconfiguration (their threads start here).
  void start();
  /// Stops every thread and callback, then drops what they use; the destructor, and a
  /// constructor that throws after start() began. Safe on a partly started server.
  void shutDown() noexcept;

  /// After a build or a request: returns freed heap to the system once much has been freed
  /// (a 4000 x 4000 map's planner frees tens of MB that glibc would otherwise keep).
  void releaseFreedMemory();
  std::shared_ptr<std::atomic<bool>> newCancelFlag();
  void releaseCancelFlag(const std::shared_ptr<std::atomic<bool>>& flag);

  ros::NodeHandle nh_, pnh_;
  /// The parameters read at start-up. Those dynamic_reconfigure cannot change (frames, queue
  /// length, map size cap, release_freed_memory) are read from here, without a lock.
  const PlannerParams startup_;
  ParamsInForce params_;

  ros::CallbackQueue service_queue_, action_queue_;
  std::unique_ptr<ros::AsyncSpinner> service_spinner_, action_spinner_;
  ros::ServiceServer plan_srv_, make_plan_srv_;
  ros::Publisher solutions_pub_, path_pub_, markers_pub_;
  std::unique_ptr<ActionServer> action_server_;

  tf2_ros::Buffer tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;

  /// The maps and their planner; stopped, then reset, before the members it uses.
  std::unique_ptr<MapTracker> map_tracker_;

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
