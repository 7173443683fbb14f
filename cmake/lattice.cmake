# The (x, y, theta) lattice domain: maps, motion primitives, footprints, heuristics and the
# LatticePlanner facade (ROS-free), plus `amha plan` and `amha bench lattice`.
find_package(yaml-cpp REQUIRED)
find_package(OpenCV REQUIRED COMPONENTS core imgproc imgcodecs)

add_library(amha_lattice
  src/lattice/occupancy.cpp
  src/lattice/map_server_map.cpp
  src/lattice/movingai_map.cpp
  src/lattice/sbpl_environment.cpp
  src/lattice/primitive_set.cpp
  src/lattice/mprim_reader.cpp
  src/lattice/mprim_writer.cpp
  src/lattice/primitive_generator.cpp
  src/lattice/footprint.cpp
  src/lattice/lattice_graph.cpp
  src/lattice/heuristic_grids.cpp
  src/lattice/coarse_lattice.cpp
  src/lattice/lattice_problem.cpp
  src/lattice/lattice_planner.cpp
)
target_include_directories(amha_lattice PUBLIC
  $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:include>)
target_include_directories(amha_lattice SYSTEM PRIVATE ${OpenCV_INCLUDE_DIRS})
target_link_libraries(amha_lattice PUBLIC amha_search PRIVATE yaml-cpp ${OpenCV_LIBS} Threads::Threads)

target_sources(amha PRIVATE
  src/cli/lattice_options.cpp
  src/cli/lattice_image.cpp
  src/cli/plan_command.cpp
  src/cli/bench_command.cpp
  src/cli/bench_lattice.cpp
)
target_link_libraries(amha PRIVATE amha_lattice)

amha_add_gtest(amha_lattice_tests
  SOURCES
    test/lattice/test_support.cpp
    test/lattice/path_validator.cpp
    test/lattice/map_loaders_test.cpp
    test/lattice/mprim_test.cpp
    test/lattice/footprint_test.cpp
    test/lattice/heuristics_test.cpp
    test/lattice/planner_test.cpp
  LIBS amha_lattice ${OpenCV_LIBS})
target_include_directories(amha_lattice_tests SYSTEM PRIVATE ${OpenCV_INCLUDE_DIRS})
