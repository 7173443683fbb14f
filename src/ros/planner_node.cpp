// planner_node: the planning server as a standalone node (same code as PlannerNodelet).
#include <exception>

#include <ros/ros.h>

#include "amha_planner/ros/planner_server.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "amha_planner");
  ros::NodeHandle nh, pnh("~");
  try {
    amha_planner::PlannerServer server(nh, pnh);
    ros::waitForShutdown();
  } catch (const std::exception& e) {
    ROS_FATAL("amha_planner: not starting: %s", e.what());
    return 1;
  }
  return 0;
}
