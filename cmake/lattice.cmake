# The (x, y, theta) lattice domain: maps, motion primitives, footprints, heuristics and the
# LatticePlanner facade (ROS-free), plus `amha plan` and `amha bench lattice`.
find_package(yaml-cpp REQUIRED)
find_package(OpenCV REQUIRED COMPONENTS core imgproc)

add_library(amha_lattice
  src/lattice/occupancy.cpp
  src/lattice/map_server_map.cpp
  src/lattice/image_file.cpp
  src/lattice/movingai_map.cpp
  src/lattice/sbpl_environment.cpp
  src/lattice/primitive_set.cpp
  src/lattice/mprim_reader.cpp
  src/lattice/mprim_writer.cpp
  src/lattice/primitive_generator.cpp
  src/lattice/footprint.cpp
  src/lattice/lattice_graph.cpp
  src/lattice/grid_moves.cpp
  src/lattice/heuristic_grids.cpp
  src/lattice/displacement_grid.cpp
  src/lattice/coarse_lattice.cpp
  src/lattice/kinematic_table.cpp
  src/lattice/lattice_problem.cpp
  src/lattice/lattice_planner.cpp
  src/lattice/goal_tolerance.cpp
  src/lattice/goal_reachability.cpp
  src/lattice/start_escape.cpp
  src/lattice/dubins_path.cpp
  src/lattice/path_smoother.cpp
)
target_include_directories(amha_lattice PUBLIC
  $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:include>)
target_include_directories(amha_lattice SYSTEM PRIVATE ${OpenCV_INCLUDE_DIRS})
target_include_directories(amha_lattice PRIVATE src/image_codecs)
# No opencv_imgcodecs: image files go through the module of image_codecs.cmake, loaded on first
# use (image_file.h); building anything that links amha_lattice builds the module too.
target_link_libraries(amha_lattice PUBLIC amha_search
                      PRIVATE yaml-cpp opencv_core opencv_imgproc ${CMAKE_DL_LIBS} Threads::Threads)
add_dependencies(amha_lattice amha_image_codecs)
set_target_properties(amha_lattice PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${AMHA_LIBRARY_DIR})

target_sources(amha PRIVATE
  src/cli/lattice_options.cpp
  src/cli/lattice_image.cpp
  src/cli/plan_command.cpp
  src/cli/bench_command.cpp
  src/cli/bench_lattice.cpp
  src/cli/bench_replan.cpp
  src/cli/bench_smooth.cpp
  src/cli/path_metrics.cpp
)
target_link_libraries(amha PRIVATE amha_lattice)
# The benchmarks stamp their reports with this tree's commit.
set_source_files_properties(src/cli/bench_command.cpp PROPERTIES COMPILE_DEFINITIONS
                            "AMHA_SOURCE_DIR=\"${CMAKE_SOURCE_DIR}\"")

# The replanning benchmark on the bundled map: the repaired chain's grids must be repaired
# after every update, and both chains must find the same first solutions (else exit 1).
add_test(NAME amha_bench_replan_repairs_and_agrees
         COMMAND ${CMAKE_SOURCE_DIR}/test/cli/bench_replan_test.sh $<TARGET_FILE:amha> ${CMAKE_SOURCE_DIR}/maps/willow_garage/willow-2010-02-18-0.10.yaml)

# Bad option values are refused with a usage error naming the option, absurd robots and coarse
# blocks up front, and the time budget holds during the planner's setup (issue 22).
add_test(NAME amha_plan_refusals
         COMMAND ${CMAKE_SOURCE_DIR}/test/cli/plan_refusals_test.sh $<TARGET_FILE:amha>
                 ${CMAKE_SOURCE_DIR}/maps/willow_garage/willow-2010-02-18-0.10.yaml
                 ${CMAKE_SOURCE_DIR}/test/lattice/data/nav2_diff_8_headings.json)

# amha plan's switches keep the lattice preset's values when absent; --json records the search.
add_test(NAME amha_plan_search_flags
         COMMAND ${CMAKE_SOURCE_DIR}/test/cli/plan_search_flags_test.sh $<TARGET_FILE:amha>
                 ${CMAKE_SOURCE_DIR}/maps/willow_garage/willow-2010-02-18-0.10.yaml)

# Contradicting flags are refused with a usage error (exit code 2), not silently resolved.
add_test(NAME amha_plan_refuses_both_turn_flags
         COMMAND ${CMAKE_SOURCE_DIR}/test/cli/plan_turn_flags_test.sh $<TARGET_FILE:amha>)

# A goal on a wall of the bundled map: refused (exit 6) without a goal tolerance, replaced by a
# reachable free pose with one.
add_test(NAME amha_plan_goal_tolerance
         COMMAND ${CMAKE_SOURCE_DIR}/test/cli/plan_goal_tolerance_test.sh $<TARGET_FILE:amha> ${CMAKE_SOURCE_DIR}/maps/willow_garage/willow-2010-02-18-0.10.yaml)

# A start on a wall of the bundled map: refused (exit 5) without a start tolerance; with one the
# path leaves the wall first and says how, and the JSON marks the escape; a tolerance too small
# to reach a free pose is refused again, naming it.
add_test(NAME amha_plan_start_tolerance
         COMMAND ${CMAKE_SOURCE_DIR}/test/cli/plan_start_tolerance_test.sh $<TARGET_FILE:amha> ${CMAKE_SOURCE_DIR}/maps/willow_garage/willow-2010-02-18-0.10.yaml)

# A free goal heading on the bundled map: A* proves a cheaper optimum than with the goal's own
# heading (72719 against 73316 cost units, measured) and says where it ended.
add_test(NAME amha_plan_any_goal_heading
         COMMAND ${CMAKE_SOURCE_DIR}/test/cli/plan_any_goal_heading_test.sh $<TARGET_FILE:amha> ${CMAKE_SOURCE_DIR}/maps/willow_garage/willow-2010-02-18-0.10.yaml)

# A costmap read as the server reads it (--lethal-threshold 100) and --smooth, end to end, and
# the README's example on the bundled costmap.
add_test(NAME amha_plan_costmap_and_smooth
         COMMAND ${CMAKE_SOURCE_DIR}/test/cli/plan_costmap_smooth_test.sh $<TARGET_FILE:amha>
                 ${CMAKE_SOURCE_DIR}/maps/willow_garage/willow-costmap-r025.yaml)

amha_add_gtest(amha_lattice_tests
  SOURCES
    test/lattice/test_support.cpp
    test/lattice/path_validator.cpp
    test/lattice/map_loaders_test.cpp
    test/lattice/mprim_test.cpp
    test/lattice/footprint_test.cpp
    test/lattice/heuristics_test.cpp
    test/lattice/displacement_grid_test.cpp
    test/lattice/backward_bound_test.cpp
    test/lattice/planner_test.cpp
    test/lattice/incremental_map_test.cpp
    test/lattice/heuristic_repair_test.cpp
    test/lattice/background_grids_test.cpp
    test/lattice/grid_direction_test.cpp
    test/lattice/goal_tolerance_test.cpp
    test/lattice/any_goal_heading_test.cpp
    test/lattice/kinematic_table_test.cpp
    test/lattice/state_keys_test.cpp
    test/lattice/start_escape_test.cpp
    test/lattice/goal_reachability_test.cpp
    test/lattice/path_smoother_test.cpp
    test/lattice/ana_star_lattice_test.cpp
  LIBS amha_lattice opencv_core opencv_imgproc opencv_imgcodecs)  # the tests write images themselves
target_include_directories(amha_lattice_tests SYSTEM PRIVATE ${OpenCV_INCLUDE_DIRS})
target_compile_definitions(amha_lattice_tests PRIVATE "AMHA_SOURCE_DIR=\"${CMAKE_SOURCE_DIR}\"")  # the bundled map

# The codecs module stays out of processes that read no image file. No imgcodecs link here:
# the test looks for it in /proc/self/maps.
amha_add_gtest(amha_image_codecs_tests
  SOURCES test/lattice/image_codecs_test.cpp test/lattice/test_support.cpp
  LIBS amha_lattice opencv_core)
target_include_directories(amha_image_codecs_tests SYSTEM PRIVATE ${OpenCV_INCLUDE_DIRS})
