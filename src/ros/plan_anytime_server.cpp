// The ~plan_anytime action server (see plan_anytime_server.h).
#include "amha_planner/ros/plan_anytime_server.h"

#include <algorithm>
#include <utility>

#include <boost/bind/bind.hpp>
#include <boost/make_shared.hpp>

namespace amha_planner {

PlanAnytimeServer::PlanAnytimeServer(const ros::NodeHandle& nh, const std::string& name,
                                     boost::function<void(GoalHandle)> goal_cb,
                                     boost::function<void(GoalHandle)> cancel_cb)
    : Base(std::move(goal_cb), std::move(cancel_cb), /*auto_start=*/false), node_(nh, name) {}

PlanAnytimeServer::~PlanAnytimeServer() {
  // Nothing may call back into this object once its members are gone.
  status_timer_.stop();
  goal_sub_.shutdown();
  cancel_sub_.shutdown();
}

PlanAnytimeResult PlanAnytimeServer::resultWithoutPlanner(std::uint8_t goal_state,
                                                          const std::string& global_frame) {
  PlanAnytimeResult r;
  r.path.header.frame_id = global_frame;
  if (goal_state == actionlib_msgs::GoalStatus::RECALLED ||
      goal_state == actionlib_msgs::GoalStatus::PREEMPTED) {
    r.status = PlanAnytimeResult::CANCELLED;
    r.message = "cancelled before the planner received the goal: no planning was done";
  } else {
    r.status = PlanAnytimeResult::INTERNAL_ERROR;
    r.message = "the action server ended the goal without the planner";
  }
  return r;
}

void PlanAnytimeServer::initialize() {
  // The topics, queue sizes and status rate of actionlib's own server (same parameters).
  const int pub_queue = std::max(0, node_.param("actionlib_server_pub_queue_size", 50));
  const int sub_queue = std::max(0, node_.param("actionlib_server_sub_queue_size", 50));
  result_pub_ = node_.advertise<ActionResult>("result", static_cast<std::uint32_t>(pub_queue));
  feedback_pub_ =
      node_.advertise<ActionFeedback>("feedback", static_cast<std::uint32_t>(pub_queue));
  status_pub_ = node_.advertise<actionlib_msgs::GoalStatusArray>(
      "status", static_cast<std::uint32_t>(pub_queue),
      /*latch=*/true);
  double frequency = 5.0;
  std::string frequency_name;
  if (node_.searchParam("actionlib_status_frequency", frequency_name))
    node_.param(frequency_name, frequency, 5.0);
  status_list_timeout_ = ros::Duration(node_.param("status_list_timeout", 5.0));
  if (frequency > 0.0) {
    status_timer_ =
        node_.createTimer(ros::Duration(1.0 / frequency), [this](const ros::TimerEvent&) {
          boost::recursive_mutex::scoped_lock lock(lock_);
          if (started_) publishStatus();
        });
  }
  goal_sub_ =
      node_.subscribe<ActionGoal>("goal", static_cast<std::uint32_t>(sub_queue),
                                  boost::bind(&Base::goalCallback, this, boost::placeholders::_1));
  cancel_sub_ = node_.subscribe<actionlib_msgs::GoalID>(
      "cancel", static_cast<std::uint32_t>(sub_queue),
      boost::bind(&Base::cancelCallback, this, boost::placeholders::_1));
}

void PlanAnytimeServer::publishResult(const actionlib_msgs::GoalStatus& status,
                                      const Result& result) {
  boost::recursive_mutex::scoped_lock lock(lock_);
  auto out = boost::make_shared<ActionResult>();
  out->header.stamp = ros::Time::now();
  out->status = status;
  // request_id 0: not the planner's (it numbers requests from 1) but actionlib's default result.
  out->result =
      result.request_id == 0 ? resultWithoutPlanner(status.status, global_frame_) : result;
  result_pub_.publish(out);
  publishStatus();
}

void PlanAnytimeServer::publishFeedback(const actionlib_msgs::GoalStatus& status,
                                        const Feedback& feedback) {
  boost::recursive_mutex::scoped_lock lock(lock_);
  auto out = boost::make_shared<ActionFeedback>();
  out->header.stamp = ros::Time::now();
  out->status = status;
  out->feedback = feedback;
  feedback_pub_.publish(out);
}

void PlanAnytimeServer::publishStatus() {
  boost::recursive_mutex::scoped_lock lock(lock_);
  actionlib_msgs::GoalStatusArray array;
  const ros::Time now = ros::Time::now();
  array.header.stamp = now;
  array.status_list.reserve(status_list_.size());
  // Each goal is listed once more after its handles are gone, then dropped after the timeout.
  for (auto it = status_list_.begin(); it != status_list_.end();) {
    array.status_list.push_back(it->status_);
    const ros::Time gone = it->handle_destruction_time_;
    if (gone != ros::Time() && gone + status_list_timeout_ < now) {
      it = status_list_.erase(it);
    } else {
      ++it;
    }
  }
  status_pub_.publish(array);
}

}  // namespace amha_planner
