// The lattice search's state list: every (x, y, heading) comes back as it went in, in 4-byte
// keys where the map allows and 8-byte ones where it does not.
#include <gtest/gtest.h>

#include "amha_planner/lattice/detail/state_keys.h"

namespace amha {
namespace lattice {
namespace {

constexpr int kVirtual = 0xFFFF;

void expectRoundTrip(StateKeys& keys, int x, int y, int heading) {
  const StateId id = keys.add(x, y, heading);
  int gx = -1, gy = -1, gh = -1;
  keys.at(id, &gx, &gy, &gh);
  EXPECT_EQ(gx, x);
  EXPECT_EQ(gy, y);
  EXPECT_EQ(gh, heading);
}

TEST(StateKeys, NarrowUpToTheLastKeyThatFits) {
  // 2^27 cells at 16 headings (5 bits with the virtual code): the largest key is 2^32 - 1.
  StateKeys keys(8192, 16384, 16, kVirtual);
  ASSERT_TRUE(keys.narrow());
  expectRoundTrip(keys, 0, 0, 0);
  expectRoundTrip(keys, 8191, 16383, 15);
  expectRoundTrip(keys, 8191, 16383, kVirtual);
  expectRoundTrip(keys, 4321, 77, 9);
  EXPECT_EQ(keys.size(), 4u);
  EXPECT_GE(keys.bytes(), 4 * sizeof(std::uint32_t));
  EXPECT_LT(keys.bytes(), 4096u) << "4 bytes a state, not 8";
}

TEST(StateKeys, WideWhenTheMapIsTooLargeForFourBytes) {
  // One row more than above no longer fits; neither do 72 headings (7 bits) on 2^26 cells.
  StateKeys rows(8192, 16385, 16, kVirtual);
  EXPECT_FALSE(rows.narrow());
  expectRoundTrip(rows, 8191, 16384, 15);
  expectRoundTrip(rows, 8191, 16384, kVirtual);
  StateKeys headings(8192, 8192, 72, kVirtual);
  ASSERT_FALSE(headings.narrow());
  expectRoundTrip(headings, 8191, 8191, 71);
  expectRoundTrip(headings, 1, 8191, kVirtual);
  expectRoundTrip(headings, 8191, 0, 0);
  EXPECT_EQ(headings.size(), 3u);
}

TEST(StateKeys, IdsInOrderOfAddition) {
  StateKeys keys(10, 10, 16, kVirtual);
  for (int k = 0; k < 1000; ++k) EXPECT_EQ(keys.add(k % 10, (k / 10) % 10, k % 16), k);
  int x, y, h;
  keys.at(537, &x, &y, &h);
  EXPECT_EQ(x, 7);
  EXPECT_EQ(y, 3);
  EXPECT_EQ(h, 537 % 16);
}

}  // namespace
}  // namespace lattice
}  // namespace amha
