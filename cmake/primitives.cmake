# Motion primitives beyond SBPL's: the near-minimal generator, Nav2 lattice files (JSON), and
# `amha primitives`, which writes generated sets in either format. Part of amha_lattice.
target_sources(amha_lattice PRIVATE
  src/lattice/primitive_geometry.cpp
  src/lattice/near_minimal_generator.cpp
  src/lattice/primitive_sources.cpp
  src/lattice/nav2_lattice_reader.cpp
  src/lattice/nav2_lattice_writer.cpp
)
target_link_libraries(amha_lattice PRIVATE nlohmann_json::nlohmann_json)

target_sources(amha PRIVATE src/cli/primitive_options.cpp src/cli/primitives_command.cpp)
target_sources(amha PRIVATE src/cli/bench_primitives.cpp)

amha_add_gtest(amha_primitives_tests
  SOURCES test/lattice/near_minimal_test.cpp test/lattice/nav2_lattice_test.cpp test/lattice/test_support.cpp
  LIBS amha_lattice nlohmann_json::nlohmann_json)

if(AMHA_FUZZ)
  amha_add_fuzzer(nav2_lattice LIBS amha_lattice)
endif()

# One set through both formats from the command line: generated -> .json -> .mprim -> read,
# with the same primitives per heading at every step.
add_test(NAME amha_primitives_both_formats
         COMMAND ${CMAKE_SOURCE_DIR}/test/cli/primitives_both_formats_test.sh $<TARGET_FILE:amha>)

# `amha plan` with a Nav2 file of the map's resolution plans; of another resolution it is
# refused with exit code 4 and the file's error; bad generator options are usage errors.
add_test(NAME amha_plan_nav2_file_and_bad_options
         COMMAND ${CMAKE_SOURCE_DIR}/test/cli/plan_nav2_file_test.sh $<TARGET_FILE:amha> ${CMAKE_SOURCE_DIR}/maps/willow_garage/willow-2010-02-18-0.10.yaml
                 ${CMAKE_SOURCE_DIR}/test/lattice/data/nav2_diff_8_headings.json)
