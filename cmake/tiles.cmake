# Sliding-tile domain: the N x N puzzle as a SearchProblem, its heuristics and instances.
add_library(amha_tiles
  src/tiles/board.cpp
  src/tiles/heuristics.cpp
  src/tiles/instances.cpp
  src/tiles/tiles_problem.cpp
)
target_link_libraries(amha_tiles PUBLIC amha_search)

amha_add_gtest(amha_tiles_tests
  SOURCES
    test/tiles/board_test.cpp
    test/tiles/heuristics_test.cpp
    test/tiles/instances_test.cpp
    test/tiles/tiles_problem_test.cpp
    test/tiles/korf_search_test.cpp
  LIBS amha_tiles)

# `amha tiles`: the paper's tile experiments.
target_sources(amha PRIVATE src/cli/tiles_command.cpp src/cli/tiles_report.cpp
                            src/cli/tiles_report_command.cpp)
target_link_libraries(amha PRIVATE amha_tiles)
amha_add_gtest(amha_tiles_report_tests
  SOURCES test/tiles/tiles_report_test.cpp src/cli/tiles_report.cpp
  LIBS amha_cli_support)

# `amha tiles` end to end (exit codes, JSON, instance files).
add_test(NAME amha_tiles_cli
         COMMAND ${CMAKE_SOURCE_DIR}/test/tiles/tiles_cli_test.sh $<TARGET_FILE:amha>)
