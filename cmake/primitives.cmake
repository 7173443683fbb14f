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
         COMMAND bash -c "d=$(mktemp -d) && a=$(\"$0\" primitives --motion-model ackermann --out $d/a.json | grep 'per heading') && b=$(\"$0\" primitives --in $d/a.json --out $d/a.mprim | grep 'per heading') && c=$(\"$0\" primitives --in $d/a.mprim | grep 'per heading') && echo \"$a\" && [ -n \"$a\" ] && [ \"$a\" = \"$b\" ] && [ \"$a\" = \"$c\" ]"
                 $<TARGET_FILE:amha>)

# `amha plan` with a Nav2 file of the map's resolution plans; of another resolution it is
# refused with exit code 4 and the file's error; bad generator options are usage errors.
add_test(NAME amha_plan_nav2_file_and_bad_options
         COMMAND bash -c "args=(plan --map \"$1\" --radius 0.2 --start 17,55,0 --goal 26,6,1.57 --algorithm wastar --time-limit 10); \"$0\" \"\${args[@]}\" --mprim \"$2\" >/dev/null || exit 1; d=$(mktemp -d); \"$0\" primitives --resolution 0.05 --out $d/fine.json --quiet; out=$(\"$0\" \"\${args[@]}\" --mprim $d/fine.json 2>&1); rc=$?; echo \"$out\"; [ $rc -eq 4 ] && grep -q \"does not match the map's resolution 0.1\" <<<\"$out\" || exit 1; \"$0\" \"\${args[@]}\" --motion-model car >/dev/null 2>&1; [ $? -eq 2 ] || exit 1; \"$0\" \"\${args[@]}\" --reverse --reverse-penalty nan >/dev/null 2>&1; [ $? -eq 2 ] || exit 1; \"$0\" \"\${args[@]}\" --mprim \"$2\" --motion-model ackermann >/dev/null 2>&1; [ $? -eq 2 ]"
                 $<TARGET_FILE:amha> ${CMAKE_SOURCE_DIR}/maps/willow_garage/willow-2010-02-18-0.10.yaml
                 ${CMAKE_SOURCE_DIR}/test/lattice/data/nav2_diff_8_headings.json)
