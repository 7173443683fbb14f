# ROS layer targets: the planning server library, the nodelet and the node, the map publisher
# and demo client, the ament index pluginlib needs, and the rostest nodes.
# Only message/param conversion, tf2 and threads live here; planning is amha_lattice's.
find_library(AMHA_CLASS_LOADER_LIB class_loader REQUIRED)

# The server: shared by the nodelet and the standalone node.
add_library(amha_ros
  src/ros/conversions.cpp
  src/ros/param_specs.cpp
  src/ros/planner_params.cpp
  src/ros/plan_queue.cpp
  src/ros/latest_job_runner.cpp
  src/ros/map_tracker.cpp
  src/ros/freed_memory.cpp
  src/ros/plan_anytime_server.cpp
  src/ros/planner_server.cpp
  src/ros/response_conversion.cpp
  src/ros/reconfigure.cpp
  src/ros/request_conversion.cpp
)
target_include_directories(amha_ros PUBLIC include ${catkin_INCLUDE_DIRS})
target_link_libraries(amha_ros PUBLIC amha_lattice ${catkin_LIBRARIES} Threads::Threads)
add_dependencies(amha_ros ${PROJECT_NAME}_generate_messages_cpp ${PROJECT_NAME}_gencfg ${catkin_EXPORTED_TARGETS})

# amha_planner/PlannerNodelet, in devel/lib/libamha_planner_nodelet.so (nodelet_plugins.xml).
add_library(amha_planner_nodelet SHARED src/ros/planner_nodelet.cpp)
target_link_libraries(amha_planner_nodelet PRIVATE amha_ros ${AMHA_CLASS_LOADER_LIB})

add_executable(planner_node src/ros/planner_node.cpp)
target_link_libraries(planner_node PRIVATE amha_ros)

# Publishes a map_server YAML + image as a latched OccupancyGrid (map_server is not in Debian).
add_executable(map_publisher src/ros/map_publisher.cpp)
target_link_libraries(map_publisher PRIVATE amha_ros)

# The demo's client: asks for a plan, prints every improvement, draws them on the map.
add_executable(demo_client src/ros/demo_client.cpp)
target_include_directories(demo_client PRIVATE ${OpenCV_INCLUDE_DIRS})
target_link_libraries(demo_client PRIVATE amha_ros opencv_core opencv_imgproc)  # PNG: image_file.h

# Debian's pluginlib 5 finds nodelets through the ament resource index of each prefix in
# AMENT_PREFIX_PATH; write it into the devel space (and install it below).
set(_amha_index ${CATKIN_DEVEL_PREFIX}/share/ament_index/resource_index)
file(WRITE ${_amha_index}/packages/${PROJECT_NAME} "")
file(WRITE ${_amha_index}/nodelet__pluginlib__plugin/${PROJECT_NAME}
     "share/${PROJECT_NAME}/nodelet_plugins.xml")
configure_file(nodelet_plugins.xml ${CATKIN_DEVEL_PREFIX}/share/${PROJECT_NAME}/nodelet_plugins.xml
               COPYONLY)
configure_file(package.xml ${CATKIN_DEVEL_PREFIX}/share/${PROJECT_NAME}/package.xml COPYONLY)

# The libraries the nodelet loads (catkin builds them shared) and the image codecs module they
# dlopen from their own directory go to the install space too.
foreach(_lib amha_search amha_lattice amha_image_codecs)
  if(TARGET ${_lib})
    install(TARGETS ${_lib} LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
            ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
  endif()
endforeach()
install(TARGETS amha_ros amha_planner_nodelet
        LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
        ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
install(TARGETS planner_node map_publisher demo_client
        RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
install(DIRECTORY include/amha_planner DESTINATION ${CATKIN_GLOBAL_INCLUDE_DESTINATION})
install(FILES nodelet_plugins.xml package.xml DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})
install(DIRECTORY launch config maps DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})
install(FILES ${_amha_index}/packages/${PROJECT_NAME}
        DESTINATION share/ament_index/resource_index/packages)
install(FILES ${_amha_index}/nodelet__pluginlib__plugin/${PROJECT_NAME}
        DESTINATION share/ament_index/resource_index/nodelet__pluginlib__plugin)
# ... and sourcing a workspace's setup.bash puts that workspace (devel or install space) on
# AMENT_PREFIX_PATH, so that roslaunch finds the nodelet without any export by hand.
catkin_add_env_hooks(50.amha_planner_ament_prefix SHELLS sh DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/cmake/env-hooks)

# Unit tests of the message conversions, the requests and the responses (the request queue's
# are in robustness.cmake: ROS-free).
amha_add_gtest(amha_ros_unit_tests
  SOURCES test/ros/conversions_test.cpp test/ros/request_conversion_test.cpp
          test/ros/response_conversion_test.cpp test/ros/param_specs_test.cpp
  LIBS amha_ros yaml-cpp)
# param_specs_test holds config/planner.yaml and docs/ros.md to the parameter list.
target_compile_definitions(amha_ros_unit_tests PRIVATE "AMHA_SOURCE_DIR=\"${CMAKE_SOURCE_DIR}\"")

# rostest nodes (test/ros/*.test, run by scripts/test). Built with everything, into the devel
# space, so that rostest finds them by package and name.
function(amha_add_rostest_node name)
  add_executable(${name} ${ARGN})
  target_link_libraries(${name} PRIVATE amha_ros GTest::gtest)
endfunction()
amha_add_rostest_node(planner_rostest test/ros/planner_rostest.cpp test/ros/rostest_support.cpp)
amha_add_rostest_node(no_map_rostest test/ros/no_map_rostest.cpp test/ros/rostest_support.cpp)
amha_add_rostest_node(reconfigure_rostest test/ros/reconfigure_rostest.cpp test/ros/rostest_support.cpp)
amha_add_rostest_node(action_results_rostest test/ros/action_results_rostest.cpp test/ros/rostest_support.cpp)
add_executable(static_tf_publisher test/ros/static_tf_publisher.cpp)
target_link_libraries(static_tf_publisher PRIVATE amha_ros)
