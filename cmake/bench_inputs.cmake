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
         COMMAND bash -c "d=$(mktemp -d) && for s in a:3 b:3 c:4; do \"$0\" map random --width 300 --height 200 --obstacles 0.15 --seed \${s#*:} --out $d/\${s%:*} >/dev/null || exit 1; done; cmp $d/a.pgm $d/b.pgm && cmp $d/a.yaml <(sed s/b.pgm/a.pgm/ $d/b.yaml) && ! cmp -s $d/a.pgm $d/c.pgm && \"$0\" bench queries --map $d/a.yaml --radius 0.2 --count 3 >/dev/null"
                 $<TARGET_FILE:amha>)

# The same seed prints the same pairs, another seed others; every pair is at least
# --min-distance apart (validity and connectivity: amha_bench_inputs_tests).
add_test(NAME amha_bench_queries_seeded_and_far_apart
         COMMAND bash -c "m=\"$1\"; q() { \"$0\" bench queries --map \"$m\" --radius 0.2 --count 8 --min-distance 15 --seed $1; }; a=$(q 1) && b=$(q 1) && c=$(q 2) || exit 1; echo \"$a\"; [ \"$a\" = \"$b\" ] && [ \"$a\" != \"$c\" ] && [ $(wc -l <<<\"$a\") -eq 8 ] && awk -F'[, ]' '{ d = sqrt(($4 - $1)^2 + ($5 - $2)^2); if (d < 15) { print \"too close: \" $0; bad = 1 } } END { exit bad }' <<<\"$a\""
                 $<TARGET_FILE:amha> ${CMAKE_SOURCE_DIR}/maps/willow_garage/willow-2010-02-18-0.10.yaml)
