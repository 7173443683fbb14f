# The search core: algorithms only; depends on neither ROS nor OpenCV.
add_library(amha_search
  src/search/planner_config.cpp
  src/search/stop_condition.cpp
  src/search/large_blocks.cpp
  src/search/map_large_blocks_alone.cpp
  src/search/search_base.cpp
  src/search/dts_schedule.cpp
  src/search/mha_engine.cpp
  src/search/ana_star.cpp
  src/search/planner_factory.cpp
)
target_include_directories(amha_search PUBLIC
  $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:include>)

amha_add_gtest(amha_search_tests
  SOURCES
    test/search/test_graphs.cpp
    test/search/bucket_queue_test.cpp
    test/search/key_bucket_queue_test.cpp
    test/search/realloc_vector_test.cpp
    test/search/indexed_heap_test.cpp
    test/search/optimality_test.cpp
    test/search/weight_schedule_test.cpp
    test/search/limits_test.cpp
    test/search/goal_unreachable_test.cpp
    test/search/stop_condition_test.cpp
    test/search/algorithm_specs_test.cpp
    test/search/monotone_cost_test.cpp
    test/search/dts_schedule_test.cpp
    test/search/ana_star_test.cpp
    test/search/inflation_bases_test.cpp
    test/search/heuristic_upgrade_test.cpp
  LIBS amha_search)

if(AMHA_FUZZ)
  add_library(amha_search_test_graphs STATIC test/search/test_graphs.cpp)
  target_link_libraries(amha_search_test_graphs PUBLIC amha_search)
  amha_add_fuzzer(search LIBS amha_search_test_graphs)
endif()
