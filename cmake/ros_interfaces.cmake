# ROS: catkin, message/service/action generation and catkin_package(). Sets AMHA_HAVE_ROS.
# Included before the rest of the build because catkin sets the output directories (devel space).
set(AMHA_ROS_COMPONENTS
  roscpp nodelet std_msgs geometry_msgs nav_msgs map_msgs visualization_msgs actionlib
  actionlib_msgs tf2 tf2_ros tf2_geometry_msgs message_generation dynamic_reconfigure)
find_package(catkin QUIET COMPONENTS ${AMHA_ROS_COMPONENTS})
if(catkin_FOUND)
  set(AMHA_HAVE_ROS ON)
  add_message_files(DIRECTORY msg FILES PlanSolution.msg)
  add_service_files(DIRECTORY srv FILES Plan.srv)
  add_action_files(DIRECTORY action FILES PlanAnytime.action)
  generate_messages(DEPENDENCIES std_msgs geometry_msgs nav_msgs actionlib_msgs)
  # The parameters that may change at run time (AmhaPlannerConfig.h, rqt_reconfigure).
  generate_dynamic_reconfigure_options(cfg/AmhaPlanner.cfg)
  catkin_package(
    INCLUDE_DIRS include
    LIBRARIES amha_search amha_lattice amha_ros
    CATKIN_DEPENDS roscpp nodelet std_msgs geometry_msgs nav_msgs map_msgs visualization_msgs
                   actionlib actionlib_msgs tf2 tf2_ros tf2_geometry_msgs message_runtime dynamic_reconfigure)
else()
  message(STATUS "catkin or one of its components (${AMHA_ROS_COMPONENTS}) not found: "
                 "building without the ROS layer")
endif()
