# libFuzzer targets (clang only): configure with CXX=clang++ -DAMHA_FUZZ=ON -DAMHA_BUILD_ROS=OFF.
# Each target is test/fuzz/<name>_fuzzer.cpp with a seed corpus in test/fuzz/corpus/<name>/.
add_custom_target(amha_fuzzers)
function(amha_add_fuzzer name)
  cmake_parse_arguments(ARG "" "" "LIBS" ${ARGN})
  add_executable(${name}_fuzzer test/fuzz/${name}_fuzzer.cpp)
  target_compile_options(${name}_fuzzer PRIVATE -fsanitize=fuzzer,address,undefined)
  target_link_options(${name}_fuzzer PRIVATE -fsanitize=fuzzer,address,undefined)
  target_link_libraries(${name}_fuzzer PRIVATE ${ARG_LIBS})
  set_target_properties(${name}_fuzzer PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/fuzz)
  add_dependencies(amha_fuzzers ${name}_fuzzer)
endfunction()
