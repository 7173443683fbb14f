# Robustness tests: the lattice's limits (big maps, memory caps, huge or negative sizes, a
# cancel during the heuristic grids), regressions found by fuzzing, and the server's job queues
# (requests, map builds) and freed-memory release, which are ROS-free: built without ROS too, so
# the ThreadSanitizer pass runs them.
amha_add_gtest(amha_lattice_limits_tests
  SOURCES
    test/lattice/test_support.cpp
    test/lattice/path_validator.cpp
    test/lattice/lattice_limits_test.cpp
    test/lattice/lattice_regression_test.cpp
  LIBS amha_lattice)

amha_add_gtest(amha_server_queue_tests
  SOURCES
    test/ros/plan_queue_test.cpp
    test/ros/latest_job_runner_test.cpp
    test/ros/freed_memory_test.cpp
    src/ros/plan_queue.cpp
    src/ros/latest_job_runner.cpp
    src/ros/freed_memory.cpp
  LIBS amha_lattice)

amha_add_gtest(amha_tiles_regression_tests
  SOURCES test/tiles/tiles_regression_test.cpp
  LIBS amha_tiles)
