// The planning server (see planner_server.h): the request queue, cancels and tf2. The maps and
// their planner are MapTracker's; requests and responses are request_conversion.h's and
// response_conversion.h's.
#include "amha_planner/ros/planner_server.h"

#include <chrono>
#include <future>
#include <utility>

#include <tf2/exceptions.h>
#include <tf2_geometry_msgs/tf2_geometry_msgs.h>
#include <visualization_msgs/MarkerArray.h>

#include "amha_planner/lattice/path_smoother.h"
#include "amha_planner/ros/conversions.h"
#include "amha_planner/ros/reconfigure.h"
#include "amha_planner/ros/response_conversion.h"
#include "amha_planner/search/detail/memory_reuse.h"

namespace amha_planner {

namespace lat = amha::lattice;
using Status = Plan::Response;

namespace {

/// Blocks of this size or more are mapped alone (~release_freed_memory): a 4000 x 4000 map's
/// arrays are tens of MB each, a request's small vectors far below.
constexpr std::size_t kLargeBlockBytes = std::size_t{4} << 20;

}  // namespace

PlannerServer::PlannerServer(const ros::NodeHandle& nh, const ros::NodeHandle& pnh)
    : nh_(nh), pnh_(pnh), startup_(loadPlannerParams(pnh)), params_(startup_) {
  if (startup_.release_freed_memory && !amha::mapLargeBlocksAlone(kLargeBlockBytes)) {
    ROS_WARN(
        "amha_planner: could not set malloc's mmap threshold; replaced maps may stay resident");
  }
  queue_ = std::make_unique<PlanQueue>(static_cast<std::size_t>(startup_.max_queued_requests));
  // Threads start below (the map's, the spinners'); if a later step throws, they are stopped
  // before the members they use are destroyed, as the destructor would (it does not run then).
  try {
    start();
  } catch (...) {
    shutDown();
    throw;
  }
}

void PlannerServer::start() {
  tf_listener_ = std::make_unique<tf2_ros::TransformListener>(tf_buffer_);

  // Publishers are thread-safe; they live on the private handle (~solutions, ~plan, ~footprints).
  solutions_pub_ = pnh_.advertise<PlanSolution>("solutions", 32);
  path_pub_ = pnh_.advertise<nav_msgs::Path>("plan", 1, /*latch=*/true);
  markers_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("footprints", 1, /*latch=*/true);

  map_tracker_ = std::make_unique<MapTracker>(
      nh_, startup_, params_,
      [this](const std::string& frame, const ros::Time& stamp, double timeout) {
        return lookupTransform(startup_.global_frame, frame, stamp, timeout, nullptr);
      },
      [this] { releaseFreedMemory(); });

  ros::NodeHandle service_nh(pnh_);
  service_nh.setCallbackQueue(&service_queue_);
  plan_srv_ = service_nh.advertiseService("plan", &PlannerServer::onPlan, this);
  make_plan_srv_ = service_nh.advertiseService("make_plan", &PlannerServer::onMakePlan, this);

  ros::NodeHandle action_nh(pnh_);
  action_nh.setCallbackQueue(&action_queue_);
  action_server_ = std::make_unique<ActionServer>(
      action_nh, "plan_anytime", [this](GoalHandle g) { onGoal(g); },
      [this](GoalHandle g) { onCancel(g); });
  action_server_->setGlobalFrame(startup_.global_frame);
  action_server_->start();

  // Waiting service calls each hold a thread; one more answers BUSY while the queue is full.
  service_spinner_ = std::make_unique<ros::AsyncSpinner>(
      static_cast<std::uint32_t>(startup_.max_queued_requests + 2), &service_queue_);
  action_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &action_queue_);
  map_tracker_->start();
  service_spinner_->start();
  action_spinner_->start();

  // ~set_parameters (rqt_reconfigure), starting from the loaded values rather than the .cfg's
  // defaults; its services run on the node's own callback queue.
  reconfigure_ =
      std::make_unique<dynamic_reconfigure::Server<AmhaPlannerConfig>>(reconfigure_mutex_, pnh_);
  reconfigure_->updateConfig(configFromParams(startup_));
  reconfigure_->setCallback(
      [this](AmhaPlannerConfig& c, std::uint32_t level) { onReconfigure(c, level); });

  ROS_INFO_STREAM("amha_planner: ready; algorithm "
                  << amha::algorithmName(startup_.algorithm) << ", global frame '"
                  << startup_.global_frame << "', robot frame '" << startup_.robot_base_frame
                  << "', waiting for a map on " << map_tracker_->mapTopic());
}

PlannerServer::~PlannerServer() { shutDown(); }

void PlannerServer::shutDown() noexcept {
  reconfigure_.reset();  // no reconfiguration while the rest goes
  shutting_down_ = true;
  {
    std::lock_guard<std::mutex> lock(flags_mutex_);
    for (const auto& flag : cancel_flags_) *flag = true;
  }
  // Stop taking callbacks; waiting service threads return as their cancelled jobs finish.
  // Any of these may not exist yet when a throwing constructor calls this.
  if (map_tracker_) map_tracker_->stop();  // stops a build under way, drops one waiting
  if (action_spinner_) action_spinner_->stop();
  if (service_spinner_) service_spinner_->stop();
  queue_.reset();
  action_server_.reset();
  map_tracker_.reset();
  plan_srv_.shutdown();
  make_plan_srv_.shutdown();
}

std::shared_ptr<const PlannerParams> PlannerServer::params() const { return params_.get(); }

void PlannerServer::onReconfigure(AmhaPlannerConfig& config, std::uint32_t) {
  const std::shared_ptr<const PlannerParams> current = params();
  const AmhaPlannerConfig in_force = configFromParams(*current);
  const std::uint32_t changed = in_force.__level__(config);
  if (changed == 0) return;  // (also the call at start-up, with the loaded values)
  const bool rebuild = (changed & kReconfigureRebuild) != 0;
  auto next = std::make_shared<PlannerParams>();
  std::string error;
  bool ok = paramsFromConfig(config, *current, pnh_, next.get(), &error);
  if (ok && rebuild) {
    const auto planner = map_tracker_->currentPlanner();
    ok = latticeBuilds(*next, planner ? &planner->map() : nullptr, &error);
  }
  const std::string what = changedParameters(in_force, config);
  if (!ok) {
    ROS_ERROR("amha_planner: reconfiguration refused (%s): %s; the parameters stay as they were",
              what.c_str(), error.c_str());
    config = in_force;  // what the reply (and rqt_reconfigure) then shows
    return;
  }
  const bool have_map = map_tracker_->setParams(std::move(next), rebuild);
  ROS_INFO("amha_planner: reconfigured: %s; %s", what.c_str(),
           !rebuild ? "in force for the requests that start planning from now on"
           : have_map
               ? "rebuilding the planner from the current map (requests from now on wait for it)"
               : "in force from the first map");
}

void PlannerServer::releaseFreedMemory() {
  if (!startup_.release_freed_memory) return;  // start-up only: see the constructor
  const FreedMemory f = freed_memory_.releaseIfMuchFreed();
  if (f.trimmed) {
    ROS_DEBUG("amha_planner: returned freed memory to the system (%.0f MB free in the heap)",
              f.free_bytes / 1e6);
  }
}

std::shared_ptr<std::atomic<bool>> PlannerServer::newCancelFlag() {
  auto flag = std::make_shared<std::atomic<bool>>(false);
  std::lock_guard<std::mutex> lock(flags_mutex_);
  if (shutting_down_) *flag = true;
  cancel_flags_.insert(flag);
  return flag;
}

void PlannerServer::releaseCancelFlag(const std::shared_ptr<std::atomic<bool>>& flag) {
  std::lock_guard<std::mutex> lock(flags_mutex_);
  cancel_flags_.erase(flag);
}

geometry_msgs::TransformStamped PlannerServer::lookupTransform(const std::string& target,
                                                               const std::string& source,
                                                               const ros::Time& time,
                                                               double timeout,
                                                               const std::atomic<bool>* cancel) {
  // canTransform in slices instead of one wait of tf_timeout: a cancel ends the wait at once.
  const auto until = std::chrono::steady_clock::now() +
                     std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                         std::chrono::duration<double>(timeout));
  while (!tf_buffer_.canTransform(target, source, time, ros::Duration(0.01))) {
    if (cancel != nullptr && *cancel) throw TransformCancelled();
    if (std::chrono::steady_clock::now() >= until) break;  // lookupTransform says why
  }
  return tf_buffer_.lookupTransform(target, source, time);
}

bool PlannerServer::toGlobalFrame(const geometry_msgs::PoseStamped& in, bool is_start,
                                  double tf_timeout, geometry_msgs::PoseStamped* out,
                                  Plan::Response* res, const std::atomic<bool>& cancel) {
  const char* what = is_start ? "start" : "goal";
  const std::string& global = startup_.global_frame;
  std::string frame = normaliseFrame(in.header.frame_id);
  if (frame.empty() && is_start) {
    // The robot's current pose.
    try {
      const auto t =
          lookupTransform(global, startup_.robot_base_frame, ros::Time(0), tf_timeout, &cancel);
      out->header = t.header;
      out->header.frame_id = global;
      out->pose.position.x = t.transform.translation.x;
      out->pose.position.y = t.transform.translation.y;
      out->pose.position.z = t.transform.translation.z;
      out->pose.orientation = t.transform.rotation;
    } catch (const tf2::TransformException& e) {
      res->status = Status::TF_ERROR;
      res->message = "start has no frame, so the robot's pose is used, but the transform " +
                     global + " <- " + startup_.robot_base_frame + " is unavailable: " + e.what();
      return false;
    }
    std::string why;
    if (!checkPose(out->pose, &why)) {
      res->status = Status::INVALID_START;
      res->message = "the robot's pose from tf is unusable: " + why;
      return false;
    }
    return true;
  }
  if (frame.empty()) frame = global;
  std::string why;
  if (!checkPose(in.pose, &why)) {
    res->status = is_start ? Status::INVALID_START : Status::INVALID_GOAL;
    res->message = std::string(what) + " pose: " + why;
    return false;
  }
  if (frame == global) {
    *out = in;
    out->header.frame_id = global;
    return true;
  }
  try {
    const auto t = lookupTransform(global, frame, in.header.stamp, tf_timeout, &cancel);
    tf2::doTransform(in, *out, t);
  } catch (const tf2::TransformException& e) {
    res->status = Status::TF_ERROR;
    res->message = std::string("cannot transform the ") + what + " from '" + frame + "' to '" +
                   global + "': " + e.what();
    return false;
  }
  return true;
}

Plan::Response PlannerServer::execute(const PlannerRequest& r, std::uint32_t id,
                                      const std::atomic<bool>& cancel, const SolutionSink& sink) {
  const std::string& frame = startup_.global_frame;
  const ros::Time stamp = ros::Time::now();
  Plan::Response res = responseWithoutPath(id, Status::INTERNAL_ERROR, "", frame, stamp);
  const auto answer = [&res](std::uint32_t status, std::string message) {  // without planning
    res.status = status;
    res.message = std::move(message);
    return std::move(res);
  };
  try {
    if (shutting_down_) return answer(Status::CANCELLED, "the planner is shutting down");
    if (cancel) return answer(Status::CANCELLED, "cancelled before planning started");
    // The parameters in force when the request starts planning hold for the whole of it,
    // whatever changes meanwhile (its budget, transforms and search).
    const std::shared_ptr<const PlannerParams> params = this->params();
    PlanQuery query;
    std::string error;
    if (!queryFor(r, *params, &query, &error)) return answer(Status::INVALID_REQUEST, error);
    // The budget counts from here: the transforms and the wait for the newest map's planner use
    // it too. Poses come first: their errors do not depend on the map.
    const auto started = std::chrono::steady_clock::now();
    const auto deadline =
        started + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                      std::chrono::duration<double>(std::min(query.time_budget, 1e9)));
    geometry_msgs::PoseStamped start, goal;
    try {
      if (!toGlobalFrame(r.start, true, params->tf_timeout, &start, &res, cancel)) return res;
      if (!toGlobalFrame(r.goal, false, params->tf_timeout, &goal, &res, cancel)) return res;
    } catch (const TransformCancelled&) {
      return answer(Status::CANCELLED, "cancelled while waiting for a transform");
    }
    // Every map and update received before this request is in the planner it gets (at most
    // the build under way and one more); it keeps that planner even if a new map arrives.
    switch (map_tracker_->waitForCurrentPlanner(cancel, shutting_down_, deadline)) {
      case MapTracker::Wait::kReady:
        break;
      case MapTracker::Wait::kCancelled:
        return answer(Status::CANCELLED,
                      shutting_down_ ? "the planner is shutting down"
                                     : "cancelled while the newest map's planner was being built");
      case MapTracker::Wait::kTimeUp:
        return answer(
            Status::TIME_EXHAUSTED,
            budgetUsedUp(query.time_budget) + " while the newest map's planner was being built");
    }
    const auto planner = map_tracker_->currentPlanner();
    if (!planner) {
      return answer(Status::NO_MAP,
                    noMapMessage(map_tracker_->mapTopic(), map_tracker_->refusedMapReason()));
    }
    const lat::Pose2D s = pose2DFromPose(start.pose), g = pose2DFromPose(goal.pose);

    amha::SearchLimits limits;
    const double waited =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    limits.time_limit_s = std::max(0.0, query.time_budget - waited);
    limits.cancel = &cancel;
    limits.max_memory_bytes = static_cast<std::size_t>(params->max_memory_mb * 1024.0 * 1024.0);
    std::vector<lat::Pose2D> best_poses;  // of the path published last
    const lat::PlanResult result =
        search(*planner, *params, query, s, g, limits, sink, &res, &best_poses);
    const ResponseContext context{frame, stamp, query.time_budget, params->max_memory_mb};
    completeResponse(result, best_poses, context, &res);
  } catch (const std::exception& e) {
    res.status = Status::INTERNAL_ERROR;
    res.message = std::string("planner failure: ") + e.what();
  }
  return res;
}

lat::PlanResult PlannerServer::search(lat::LatticePlanner& planner, const PlannerParams& params,
                                      const PlanQuery& query, const lat::Pose2D& s,
                                      const lat::Pose2D& g, const amha::SearchLimits& limits,
                                      const SolutionSink& sink, Plan::Response* res,
                                      std::vector<lat::Pose2D>* best_poses) {
  const std::uint32_t id = res->request_id;
  const std::string& frame = startup_.global_frame;
  const ros::Time stamp = res->path.header.stamp;
  const lat::GoalOptions& goal_options = query.goal_options;
  // Each improvement is published as it is found (~solutions, ~plan, ~footprints), smoothed
  // with ~smooth_path.
  std::unique_ptr<lat::PathSmoother> smoother;
  std::unique_ptr<lat::SmoothedStream> stream;
  if (params.smooth_path) {
    smoother = std::make_unique<lat::PathSmoother>(planner.graph());
    stream = std::make_unique<lat::SmoothedStream>(*smoother);
  }
  std::vector<amha::StateId> previous_ids;  // state ids identify a lattice path exactly
  const auto on_solution = [&](const lat::LatticeSolution& solution) {
    const bool same_lattice_path = !res->solutions.empty() && previous_ids == solution.search.path;
    previous_ids = solution.search.path;
    PlanSolution m;
    const lat::LatticeSolution* shown = &solution;
    bool smoothed = false;
    if (stream) {
      try {
        const lat::SmoothedStream::Step& step = stream->add(solution);
        m = smoothedSolutionMsg(step.published, solution, id, frame, stamp);
        m.same_path_as_previous = !res->solutions.empty() && step.same_as_previous;
        shown = &step.published;
        smoothed = true;
      } catch (const std::exception& e) {
        ROS_ERROR("amha_planner: request %u: smoothing failed, publishing the lattice path: %s", id,
                  e.what());
      }
    }
    if (!smoothed) {
      m = planSolutionMsg(solution, id, frame, stamp);
      m.same_path_as_previous = same_lattice_path;
    }
    *best_poses = shown->poses;
    solutions_pub_.publish(m);
    if (!m.same_path_as_previous) {
      path_pub_.publish(m.path);
      // With a goal tolerance or any goal heading the path may end elsewhere than at the
      // goal pose: mark where it really ends.
      const bool free_end = goal_options.tolerance > 0.0 || goal_options.any_heading;
      const lat::Pose2D& goal_mark = free_end ? shown->poses.back() : g;
      markers_pub_.publish(footprintMarkers(planner, shown->poses, s, goal_mark, frame, stamp,
                                            params.marker_spacing));
    }
    if (sink) sink(m);
    if (m.same_path_as_previous) m.path.poses.clear();  // the previous entry has it
    if (same_lattice_path) m.lattice_path.poses.clear();
    res->solutions.push_back(std::move(m));
  };
  lat::PlanResult result =
      planner.plan(s, g, query.start_options, goal_options, query.config, limits, on_solution);
  if (result.error == lat::QueryError::kNone) {
    if (result.heuristic_source == lat::HeuristicSource::kNone)
      ROS_DEBUG("request %u: ended before any heuristic grid was needed", id);
    else
      ROS_DEBUG("request %u: heuristic grids %s in %.4f s", id,
                lat::heuristicSourceName(result.heuristic_source), result.heuristic_seconds);
  }
  return result;
}

Plan::Response PlannerServer::runBlocking(const PlannerRequest& request) {
  const std::uint32_t id = next_request_id_++;
  auto done = std::make_shared<std::promise<Plan::Response>>();
  std::future<Plan::Response> response = done->get_future();
  auto flag = newCancelFlag();
  const bool queued = queue_->submit([this, request, id, flag, done] {
    done->set_value(execute(request, id, *flag, {}));
    releaseCancelFlag(flag);
    releaseFreedMemory();
  });
  if (!queued) {
    releaseCancelFlag(flag);
    return busyResponse(id, startup_.max_queued_requests, startup_.global_frame);
  }
  return response.get();
}

namespace {
void logOutcome(const char* interface, const Plan::Response& res) {
  if (res.status == Status::SUCCESS) {
    ROS_INFO("amha_planner: %s request %u: SUCCESS, %s", interface, res.request_id,
             res.message.c_str());
  } else {
    ROS_WARN("amha_planner: %s request %u: %s, %s", interface, res.request_id,
             statusCodeName(res.status), res.message.c_str());
  }
}
}  // namespace

bool PlannerServer::onPlan(Plan::Request& req, Plan::Response& res) {
  res = runBlocking(requestFrom(req));
  logOutcome("plan", res);
  return true;
}

bool PlannerServer::onMakePlan(nav_msgs::GetPlan::Request& req, nav_msgs::GetPlan::Response& res) {
  const Plan::Response out = runBlocking(requestFrom(req));
  logOutcome("make_plan", out);
  // Like move_base's make_plan: an empty plan means failure (the log says why).
  res = makePlanResponse(out, startup_.global_frame);
  return true;
}

void PlannerServer::onGoal(GoalHandle goal) {
  const PlannerRequest r = requestFrom(*goal.getGoal());
  const std::uint32_t id = next_request_id_++;
  const std::string goal_id = goal.getGoalID().id;
  auto job = std::make_shared<GoalJob>();
  job->cancel = newCancelFlag();
  job->request_id = id;

  std::lock_guard<std::mutex> lock(goals_mutex_);
  const bool queued = queue_->submit(
      [this, goal, r, id, job, goal_id]() mutable {
        { std::lock_guard<std::mutex> accepted(goals_mutex_); }  // setAccepted() has run
        int queued_phase = GoalJob::kQueued;
        if (job->phase.compare_exchange_strong(queued_phase, GoalJob::kRunning)) {
          Plan::Response res = execute(r, id, *job->cancel, [&goal](const PlanSolution& s) {
            PlanAnytimeFeedback feedback;
            feedback.solution = s;
            goal.publishFeedback(feedback);
          });
          logOutcome("plan_anytime", res);
          finishGoal(goal, std::move(res));
          job->phase = GoalJob::kDone;
          {
            std::lock_guard<std::mutex> done(goals_mutex_);
            goal_jobs_.erase(goal_id);
          }
        }  // else onCancel answered it while it waited
        releaseCancelFlag(job->cancel);
        releaseFreedMemory();
      },
      &job->ticket);
  if (!queued) {
    releaseCancelFlag(job->cancel);
    const PlanAnytimeResult busy =
        actionResult(busyResponse(id, startup_.max_queued_requests, startup_.global_frame));
    ROS_WARN("amha_planner: plan_anytime request %u: BUSY", id);
    goal.setRejected(busy, busy.message);
    return;
  }
  goal_jobs_[goal_id] = job;
  goal.setAccepted("queued as request " + std::to_string(id));
}

void PlannerServer::finishGoal(GoalHandle& goal, Plan::Response&& res) {
  const std::uint32_t status = res.status;
  const std::string message = res.message;
  const PlanAnytimeResult result = actionResult(std::move(res));
  const auto state = goal.getGoalStatus().status;
  const bool client_cancelled = state == actionlib_msgs::GoalStatus::PREEMPTING ||
                                state == actionlib_msgs::GoalStatus::RECALLING;
  if (status == Status::SUCCESS) {
    goal.setSucceeded(result, message);
  } else if (status == Status::CANCELLED && client_cancelled) {
    goal.setCanceled(result, message);
  } else {
    goal.setAborted(result, message);
  }
}

void PlannerServer::onCancel(GoalHandle goal) {
  std::lock_guard<std::mutex> lock(goals_mutex_);
  const auto it = goal_jobs_.find(goal.getGoalID().id);
  if (it == goal_jobs_.end()) return;
  const std::shared_ptr<GoalJob> job = it->second;
  *job->cancel = true;
  // A request waiting for the newest map's planner wakes now (waitForCurrentPlanner).
  map_tracker_->wakeWaiters();
  // Still in the queue: answered now, not when the request before it ends; its job skips.
  int queued_phase = GoalJob::kQueued;
  if (job->phase.compare_exchange_strong(queued_phase, GoalJob::kDone)) {
    // Its place in the queue goes to the next request at once (else the job, when the worker
    // takes it, finds it done and releases the flag itself).
    if (queue_->removeWaiting(job->ticket)) releaseCancelFlag(job->cancel);
    Plan::Response res =
        responseWithoutPath(job->request_id, Status::CANCELLED,
                            "cancelled while waiting in the queue: no planning was done",
                            startup_.global_frame, ros::Time::now());
    logOutcome("plan_anytime", res);
    finishGoal(goal, std::move(res));
    goal_jobs_.erase(it);
  }
}

}  // namespace amha_planner
