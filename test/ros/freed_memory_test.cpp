// Memory after huge maps (issue 22, item 11). A 4000 x 4000 map's planner, built and used on a
// thread of its own as the server's builder and worker are, leaves no live heap behind (no
// leak); but glibc, whose mmap threshold has risen to 32 MiB after the first such map, keeps
// tens of MB of the next ones in the thread's arena for good. How many depends on the order and
// sizes of the planner's arrays and on how far the time-limited plan gets: 113 MB before the
// lattice had kinematic tables, 9-56 MB from run to run since. With large blocks mapped alone
// it keeps a few MB at most, and the releaser returns what small blocks leave scattered in the
// arenas.
// Each test runs in a process of its own (ctest): mallopt settings are process-wide.
#include <malloc.h>

#include <chrono>
#include <fstream>
#include <iostream>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/ros/freed_memory.h"
#include "amha_planner/search/detail/memory_reuse.h"

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define AMHA_OWN_MALLOC 1
#else
#define AMHA_OWN_MALLOC 0
#endif

namespace amha_planner {
namespace {

namespace lat = amha::lattice;

double rssMb() {
  std::ifstream f("/proc/self/status");
  for (std::string line; std::getline(f, line);) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  }
  return -1.0;
}
// Bytes malloc has handed out and not got back: the live heap.
double inUseMb() {
  const struct mallinfo2 mi = mallinfo2();
  return static_cast<double>(mi.uordblks + mi.hblkhd) / (1024.0 * 1024.0);
}

std::shared_ptr<lat::GridMap> blockMap(int n, unsigned seed) {
  auto map = std::make_shared<lat::GridMap>();
  map->width = map->height = n;
  map->resolution = 0.05;
  map->cost.assign(static_cast<std::size_t>(n) * n, lat::kFreeCost);
  std::mt19937 rng(seed);
  for (int k = 0; k < n; ++k) {
    const int x0 = static_cast<int>(rng() % n), y0 = static_cast<int>(rng() % n);
    for (int y = y0; y < std::min(n, y0 + 20); ++y) {
      for (int x = x0; x < std::min(n, x0 + 20); ++x)
        map->cost[static_cast<std::size_t>(y) * n + x] = lat::kLethalCost;
    }
  }
  return map;
}

// Three 4000 x 4000 planners, each built, planned on and freed on a thread of its own; returns
// the RSS growth (MB) it leaves and checks that it leaves no live heap.
double rssKeptByHugeMaps() {
  const double rss0 = rssMb(), heap0 = inUseMb();
  for (unsigned cycle = 1; cycle <= 3; ++cycle) {
    std::thread([cycle] {
      lat::LatticePlanner planner(blockMap(4000, cycle), lat::LatticeConfig());
      amha::SearchLimits limits;
      limits.time_limit_s = 0.5;
      planner.plan({100.0, 100.0, 0.0}, {103.0, 102.0, 0.0},
                   amha::defaultConfig(amha::Algorithm::kAmhaStar), limits);
    }).join();
  }
  EXPECT_LT(inUseMb() - heap0, 2.0) << "live heap left behind: a leak";
  return rssMb() - rss0;
}

TEST(FreedMemory, GlibcsDefaultKeepsHugeMapsResidentWithoutALeak) {
  if (AMHA_OWN_MALLOC) GTEST_SKIP() << "the sanitizers replace malloc";
  const double kept = rssKeptByHugeMaps();
  std::cout << "[ memory   ] glibc's default thresholds: " << kept
            << " MB more resident after three 4000 x 4000 maps" << std::endl;
  // What glibc keeps varies too much from run to run to be checked (see the top); the figure is
  // reported, and the check is the live heap's (no leak).
}

TEST(FreedMemory, LargeBlocksMappedAloneLeaveNothingResident) {
  if (AMHA_OWN_MALLOC) GTEST_SKIP() << "the sanitizers replace malloc";
  ASSERT_TRUE(amha::mapLargeBlocksAlone(std::size_t{4} << 20));  // the server's setting
  const double kept = rssKeptByHugeMaps();
  std::cout << "[ memory   ] blocks >= 4 MiB mapped alone: " << kept
            << " MB more resident after three 4000 x 4000 maps" << std::endl;
  EXPECT_LT(kept, 10.0);
}

TEST(FreedMemory, TheReleaserReturnsFreedSmallBlocksOnceMuchIsFreed) {
  if (AMHA_OWN_MALLOC) GTEST_SKIP() << "the sanitizers replace malloc";
  FreedMemoryReleaser releaser(std::size_t{32} << 20);  // the server's
  releaser.releaseIfMuchFreed();
  // 96 MB of 64 KB blocks (below any mmap threshold), every other one then freed: the free
  // ones sit between live ones, where neither free() nor a top trim can return them.
  std::vector<char*> blocks;
  for (int k = 0; k < 1536; ++k) {
    blocks.push_back(static_cast<char*>(std::malloc(64 << 10)));
    std::fill_n(blocks.back(), 64 << 10, 1);
  }
  EXPECT_FALSE(releaser.releaseIfMuchFreed().trimmed) << "nothing freed yet";
  for (std::size_t k = 0; k < blocks.size(); k += 2) std::free(blocks[k]);
  const double rss_kept = rssMb();
  const auto t0 = std::chrono::steady_clock::now();
  const FreedMemory freed = releaser.releaseIfMuchFreed();
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const double rss1 = rssMb();
  std::cout << "[ memory   ] 48 MB freed between live blocks: RSS " << rss_kept << " -> " << rss1
            << " MB (" << freed.free_bytes / 1048576.0 << " MB free in the arenas; trim in " << ms
            << " ms)" << std::endl;
  EXPECT_TRUE(freed.trimmed);
  EXPECT_LT(rss1, rss_kept - 40.0);
  EXPECT_FALSE(releaser.releaseIfMuchFreed().trimmed) << "nothing freed since";
  for (std::size_t k = 1; k < blocks.size(); k += 2) std::free(blocks[k]);
}

}  // namespace
}  // namespace amha_planner
