# Benchmark inputs: seeded random obstacle maps (`amha map random`) and seeded start/goal pairs
# (`amha bench queries`, also used by `amha bench lattice`), so that other planners can be run on
# exactly the same maps and queries.
add_library(amha_bench_inputs STATIC src/cli/random_map.cpp src/cli/random_queries.cpp)
target_include_directories(amha_bench_inputs PUBLIC src/cli)
target_include_directories(amha_bench_inputs SYSTEM PUBLIC ${OpenCV_INCLUDE_DIRS})
target_link_libraries(amha_bench_inputs PUBLIC amha_lattice opencv_core opencv_imgproc)

target_sources(amha PRIVATE src/cli/map_command.cpp src/cli/bench_queries.cpp)
target_link_libraries(amha PRIVATE amha_bench_inputs)

amha_add_gtest(amha_bench_inputs_tests
  SOURCES test/cli/random_map_test.cpp test/lattice/test_support.cpp
  LIBS amha_bench_inputs)
target_include_directories(amha_bench_inputs_tests PRIVATE test/lattice)

# The same seed writes the same files; another seed another map; the map loads as map_server's.
add_test(NAME amha_map_random_is_seeded
         COMMAND ${CMAKE_SOURCE_DIR}/test/cli/map_random_seeded_test.sh $<TARGET_FILE:amha>)

# The same seed prints the same pairs, another seed others; every pair is at least
# --min-distance apart (validity and connectivity: amha_bench_inputs_tests).
add_test(NAME amha_bench_queries_seeded_and_far_apart
         COMMAND ${CMAKE_SOURCE_DIR}/test/cli/bench_queries_seeded_test.sh $<TARGET_FILE:amha> ${CMAKE_SOURCE_DIR}/maps/willow_garage/willow-2010-02-18-0.10.yaml)

# scripts/bench-vs-smac --report on synthetic result files: with --repeat, each query's time is
# the median of its runs (Smac itself is built outside the repository and not needed here).
add_test(NAME bench_vs_smac_report_medians
         COMMAND ${CMAKE_SOURCE_DIR}/test/cli/bench_vs_smac_report_test.py ${CMAKE_SOURCE_DIR})
