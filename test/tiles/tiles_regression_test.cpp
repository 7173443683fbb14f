// Regression tests for what fuzzing found in the tile domain (test/fuzz/tile_instances_fuzzer.cpp;
// each input is also kept in test/fuzz/corpus/tile_instances/regression-*).
#include <gtest/gtest.h>

#include <string>

#include "amha_planner/tiles/instances.h"

namespace amha {
namespace tiles {
namespace {

std::string errorOf(const std::string& text) {
  try {
    parseInstances(text, "r.txt");
  } catch (const InstanceError& e) {
    return e.what();
  }
  return "(no error)";
}

// regression-huge-optimal: an optimal length of 522222222226 was accepted and stored in an int,
// which wrapped it to a value below the Manhattan distance (the check against the Manhattan
// distance was done on the long).
TEST(InstancesRegression, OptimalLengthsBeyondIntAreRefused) {
  const std::string tiles = " 42 4 7 14 13 10 3 9 12 11 5 6 15 1 2 8 0\n";
  EXPECT_NE(errorOf("5 522222222226" + tiles)
                .find("r.txt:1: optimal length '522222222226' is not an integer in -1..1000000"),
            std::string::npos);
  EXPECT_NE(errorOf("5 2147483648" + tiles).find("is not an integer in -1..1000000"),
            std::string::npos);
  EXPECT_NE(errorOf("5 -2" + tiles).find("is not an integer in -1..1000000"), std::string::npos);
  const std::vector<Instance> ok = parseInstances("5 60" + tiles, "r.txt");
  ASSERT_EQ(ok.size(), 1u);
  EXPECT_EQ(*ok[0].optimal, 60);
}

}  // namespace
}  // namespace tiles
}  // namespace amha
