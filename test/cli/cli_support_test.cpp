// The shared output helpers: JSON run records follow the documented schema, plots are written.
#include <gtest/gtest.h>
#include <malloc.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>

#include <opencv2/imgcodecs.hpp>

#include "keep_freed_memory.h"
#include "line_plot.h"
#include "run_json.h"

namespace amha {
namespace {

TEST(RunJson, SchemaAndInfiniteBoundsAsNull) {
  SearchResult r;
  r.status = SearchStatus::kTimeLimit;
  r.expansions = 42;
  Solution s;
  s.cost = 7;
  s.nominal_bound = std::numeric_limits<double>::infinity();
  s.certified_bound = 1.5;
  r.solutions.push_back(s);
  const auto j = cli::runToJson("inst", Algorithm::kAnaStar, r, Cost{5});
  EXPECT_EQ(j["algorithm"], "ana");
  EXPECT_EQ(j["status"], "time_limit");
  EXPECT_EQ(j["optimal_cost"], 5);
  EXPECT_EQ(j["expansions"], 42);
  ASSERT_EQ(j["solutions"].size(), 1u);
  EXPECT_TRUE(j["solutions"][0]["bound"].is_null());
  EXPECT_EQ(j["solutions"][0]["certified_bound"], 1.5);
  EXPECT_TRUE(cli::runToJson("x", Algorithm::kAStar, r, std::nullopt)["optimal_cost"].is_null());
}

TEST(LinePlot, WritesAPngOfTheRequestedSize) {
  const std::string path = ::testing::TempDir() + "/plot.png";
  cli::PlotSeries a{"a", {0.1, 1, 10}, {25, 9, 1}};
  cli::PlotSeries b{"b", {0.2, 2}, {16, std::numeric_limits<double>::infinity()}};
  cli::PlotOptions o;
  o.log_x = true;
  o.width = 640;
  o.height = 400;
  cli::writeLinePlot(path, {a, b}, o);
  const cv::Mat img = cv::imread(path);
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.cols, 640);
  EXPECT_EQ(img.rows, 400);
  EXPECT_THROW(cli::writeLinePlot(path, {}, o), std::runtime_error);
  EXPECT_THROW(cli::writeLinePlot("/nonexistent-dir/x.png", {a}, o), std::runtime_error);
  std::remove(path.c_str());
}

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kOwnMalloc = true;  // the sanitizers replace malloc: mallopt does nothing there
#else
constexpr bool kOwnMalloc = false;
#endif

// Bytes glibc has mapped for blocks of their own.
std::size_t mappedBlockBytes() { return mallinfo2().hblkhd; }

// Allocates, touches and frees `bytes`; returns how much of it was a mapping of its own.
std::size_t mappedAlone(std::size_t bytes) {
  const std::size_t before = mappedBlockBytes();
  char* volatile p = static_cast<char*>(std::malloc(bytes));  // volatile: not elided
  if (p == nullptr) return 0;
  p[bytes - 1] = 1;
  const std::size_t mapped = mappedBlockBytes() - before;
  std::free(p);
  return mapped;
}

// Each test runs in a process of its own (ctest): mallopt settings are process-wide.
TEST(UnmapFreedLargeBlocks, BlocksStayMappedAloneAfterALargerOneIsFreed) {
  if (kOwnMalloc) GTEST_SKIP() << "a sanitizer's malloc";
  ASSERT_TRUE(cli::unmapFreedLargeBlocks());
  // glibc alone would raise its threshold to 8 MiB on this free, and carve the next 1 MiB block
  // from the heap, where freed memory stays resident.
  EXPECT_GE(mappedAlone(std::size_t{8} << 20), std::size_t{8} << 20);
  EXPECT_GE(mappedAlone(std::size_t{1} << 20), std::size_t{1} << 20);
  EXPECT_GE(mappedAlone(std::size_t{256} << 10), std::size_t{256} << 10);
}

}  // namespace
}  // namespace amha
