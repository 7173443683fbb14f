// The ~plan_anytime action server: actionlib's protocol (goal, cancel, status, feedback and
// result topics, status list timeout) with one change, that every result carries an honest
// status. actionlib answers by itself a goal whose cancel overtook it (RECALLED before the goal
// callback ever sees it) with a default-constructed result, whose status field reads 0, which is
// SUCCESS; here such a result says CANCELLED instead (docs/ros.md: "the result always carries
// the status code"). The planner's own results all have a request_id >= 1, which is how a
// result actionlib made is told from them.
#pragma once

#include <string>

#include <actionlib/server/action_server_base.h>
#include <actionlib_msgs/GoalStatusArray.h>
#include <ros/ros.h>

#include "amha_planner/PlanAnytimeAction.h"

namespace amha_planner {

class PlanAnytimeServer : public actionlib::ActionServerBase<PlanAnytimeAction> {
 public:
  using Base = actionlib::ActionServerBase<PlanAnytimeAction>;
  /// Serves the action `name` under `nh`; call start() once the callbacks may run.
  PlanAnytimeServer(const ros::NodeHandle& nh, const std::string& name,
                    boost::function<void(GoalHandle)> goal_cb,
                    boost::function<void(GoalHandle)> cancel_cb);
  ~PlanAnytimeServer() override;

  /// The result a goal gets when actionlib ends it without the planner: status CANCELLED for
  /// a recalled or preempted goal (INTERNAL_ERROR otherwise, which no path here produces).
  static PlanAnytimeResult resultWithoutPlanner(std::uint8_t goal_state,
                                                const std::string& global_frame);
  /// The global frame named in those results' empty path.
  void setGlobalFrame(const std::string& frame) { global_frame_ = frame; }

 private:
  void initialize() override;
  void publishResult(const actionlib_msgs::GoalStatus& status, const Result& result) override;
  void publishFeedback(const actionlib_msgs::GoalStatus& status, const Feedback& feedback) override;
  void publishStatus() override;

  ros::NodeHandle node_;
  std::string global_frame_;
  ros::Publisher result_pub_, feedback_pub_, status_pub_;
  ros::Subscriber goal_sub_, cancel_sub_;
  ros::Timer status_timer_;
};

}  // namespace amha_planner
