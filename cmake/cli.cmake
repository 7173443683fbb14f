# The `amha` command. Domains add their subcommand sources with target_sources(amha ...).
find_package(OpenCV REQUIRED COMPONENTS core imgproc)
find_package(nlohmann_json REQUIRED)
find_package(CLI11 REQUIRED)

# Helpers shared by the commands and benchmarks: JSON run records, PNG line plots, allocator
# tuning. The PNG files are written through amha_lattice's image codecs module: no imgcodecs.
add_library(amha_cli_support src/cli/run_json.cpp src/cli/line_plot.cpp
            src/cli/keep_freed_memory.cpp)
target_include_directories(amha_cli_support PUBLIC src/cli ${OpenCV_INCLUDE_DIRS})
target_link_libraries(amha_cli_support PUBLIC amha_search nlohmann_json::nlohmann_json
                      opencv_core opencv_imgproc PRIVATE amha_lattice)

add_executable(amha src/cli/main.cpp)
target_link_libraries(amha PRIVATE amha_cli_support CLI11::CLI11 Threads::Threads)
set_target_properties(amha PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/bin)

# The test reads the PNG back with OpenCV itself.
amha_add_gtest(amha_cli_tests SOURCES test/cli/cli_support_test.cpp
               LIBS amha_cli_support opencv_imgcodecs)
