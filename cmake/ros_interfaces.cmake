# ROS: catkin, message/service/action generation and catkin_package(). Sets AMHA_HAVE_ROS.
find_package(catkin QUIET COMPONENTS roscpp)
if(catkin_FOUND)
  set(AMHA_HAVE_ROS ON)
  catkin_package(INCLUDE_DIRS include LIBRARIES amha_search)
else()
  message(STATUS "catkin not found: building without the ROS layer")
endif()
