# libFuzzer targets (clang only): configure with CXX=clang++ -DAMHA_FUZZ=ON -DAMHA_BUILD_ROS=OFF.
# Each target is test/fuzz/<name>_fuzzer.cpp (plus any SOURCES) with a seed corpus in
# test/fuzz/corpus/<name>/. scripts/fuzz runs them; docs/robustness.md says how.
add_custom_target(amha_fuzzers)
function(amha_add_fuzzer name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name}_fuzzer test/fuzz/${name}_fuzzer.cpp ${ARG_SOURCES})
  target_compile_options(${name}_fuzzer PRIVATE -fsanitize=fuzzer,address,undefined)
  target_link_options(${name}_fuzzer PRIVATE -fsanitize=fuzzer,address,undefined)
  target_link_libraries(${name}_fuzzer PRIVATE ${ARG_LIBS})
  set_target_properties(${name}_fuzzer PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/fuzz)
  add_dependencies(amha_fuzzers ${name}_fuzzer)
endfunction()

# The domains' readers and the occupancy conversion (the libraries are defined later; CMake
# resolves the names when it generates the build). The search core's target is in search.cmake.
amha_add_fuzzer(mprim LIBS amha_lattice)
amha_add_fuzzer(map_server LIBS amha_lattice)
amha_add_fuzzer(movingai LIBS amha_lattice)
amha_add_fuzzer(sbpl_cfg LIBS amha_lattice)
amha_add_fuzzer(occupancy SOURCES test/lattice/path_validator.cpp LIBS amha_lattice)
amha_add_fuzzer(tile_instances LIBS amha_tiles)
