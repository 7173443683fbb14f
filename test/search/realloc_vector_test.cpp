// ReallocVector keeps its elements across growth of every size (small heap blocks, large
// blocks in their own mappings, grown with mremap), keeps them 64-byte aligned, and honours
// exact reserve, copies and moves; freed large blocks are reused only when asked for.
#include <gtest/gtest.h>

#include <malloc.h>

#include <cstdint>
#include <thread>
#include <utility>
#include <vector>

#include "amha_planner/search/detail/memory_reuse.h"
#include "amha_planner/search/detail/realloc_vector.h"

namespace amha {
namespace detail {
namespace {

bool aligned64(const void* p) { return reinterpret_cast<std::uintptr_t>(p) % 64 == 0; }

TEST(ReallocVector, KeepsElementsAndAlignmentWhileGrowingPastLargeSizes) {
  ReallocVector<std::uint32_t> v;
  // 2^24 elements (64 MiB) takes it past kLargeBlockBytes, where growth is an mremap.
  const std::uint32_t n = 1u << 24;
  for (std::uint32_t i = 0; i < n; ++i) {
    v.push_back(i * 2654435761u);
    if ((i & (i - 1)) == 0) {
      ASSERT_TRUE(aligned64(v.data())) << "after " << i;
    }
  }
  ASSERT_EQ(v.size(), n);
  for (std::uint32_t i = 0; i < n; ++i) ASSERT_EQ(v[i], i * 2654435761u) << i;
  // Interleaved with other allocations, so that small blocks move and change alignment.
  ReallocVector<std::uint64_t> a, b;
  for (std::uint64_t i = 0; i < 100000; ++i) {
    a.push_back(i);
    b.push_back(~i);
  }
  for (std::uint64_t i = 0; i < 100000; ++i) {
    ASSERT_EQ(a[i], i);
    ASSERT_EQ(b[i], ~i);
  }
  EXPECT_TRUE(aligned64(a.data()));
  EXPECT_TRUE(aligned64(b.data()));
}

TEST(ReallocVector, ReserveIsExactResizeKeepsPrefixAndClearKeepsCapacity) {
  ReallocVector<std::uint32_t> v;
  v.reserve(1000);
  EXPECT_EQ(v.capacity(), 1000u);
  EXPECT_EQ(v.size(), 0u);
  v.resize(10);
  for (std::uint32_t i = 0; i < 10; ++i) v[i] = i + 7;
  v.resize(5000);  // past the capacity: doubling would give 2000, so it takes 5000
  EXPECT_GE(v.capacity(), 5000u);
  for (std::uint32_t i = 0; i < 10; ++i) EXPECT_EQ(v[i], i + 7);
  const std::size_t cap = v.capacity();
  v.clear();
  EXPECT_TRUE(v.empty());
  EXPECT_EQ(v.capacity(), cap);
  v.reserve(10);  // never shrinks
  EXPECT_EQ(v.capacity(), cap);
}

TEST(ReallocVector, CopiesAndMovesOwnTheirElements) {
  ReallocVector<std::uint32_t> v;
  for (std::uint32_t i = 0; i < 300; ++i) v.push_back(i);
  ReallocVector<std::uint32_t> c(v);
  v[0] = 99;
  ASSERT_EQ(c.size(), 300u);
  EXPECT_EQ(c[0], 0u);
  EXPECT_EQ(c[299], 299u);
  ReallocVector<std::uint32_t> m(std::move(c));
  EXPECT_EQ(m.size(), 300u);
  EXPECT_EQ(m[299], 299u);
  EXPECT_TRUE(c.empty());  // NOLINT(bugprone-use-after-move): a moved-from vector is empty
  c = m;
  EXPECT_EQ(c[150], 150u);
  m.pop_back();
  EXPECT_EQ(m.size(), 299u);
  EXPECT_EQ(c.size(), 300u);
}

TEST(ReallocVector, LargeBlocksAreReusedOnlyWhenAskedAndKeepTheirContents) {
  setReuseFreedSearchMemory(false);
  ASSERT_EQ(pooledLargeBlockBytes(), 0u);
  constexpr std::size_t kBig = (kLargeBlockBytes / sizeof(std::uint64_t)) * 2;  // 8 MiB
  {
    ReallocVector<std::uint64_t> v;
    v.resize(kBig);
  }
  EXPECT_EQ(pooledLargeBlockBytes(), 0u) << "without reuse a freed block is unmapped";

  setReuseFreedSearchMemory(true);
  {
    ReallocVector<std::uint64_t> v;
    v.resize(kBig);
    for (std::size_t i = 0; i < kBig; ++i) v[i] = i;
  }
  EXPECT_GE(pooledLargeBlockBytes(), kBig * sizeof(std::uint64_t));
  {
    // A smaller large block takes the pooled one over (capacity stays exactly what was asked
    // for); a larger one grows it in place or by remapping, keeping what was written.
    ReallocVector<std::uint64_t> v;
    v.reserve(kBig / 2 + 1);
    EXPECT_EQ(v.capacity(), kBig / 2 + 1);
    EXPECT_EQ(pooledLargeBlockBytes(), 0u);
    v.resize(kBig);
    for (std::size_t i = 0; i < kBig; ++i) v[i] = ~i;
    v.resize(4 * kBig);
    for (std::size_t i = kBig; i < 4 * kBig; ++i) v[i] = i;
    for (std::size_t i = 0; i < kBig; ++i) ASSERT_EQ(v[i], ~i) << i;
    for (std::size_t i = kBig; i < 4 * kBig; ++i) ASSERT_EQ(v[i], i) << i;
    EXPECT_TRUE(aligned64(v.data()));
  }
  EXPECT_GE(pooledLargeBlockBytes(), 4 * kBig * sizeof(std::uint64_t));
  setReuseFreedSearchMemory(false);  // also returns the pool
  EXPECT_EQ(pooledLargeBlockBytes(), 0u);
}

TEST(ReallocVector, ReusedBlocksKeepOnlyWhatTheyNeedAndThePoolIsBounded) {
  // A small array taking a big pooled block gives the rest back: otherwise it keeps resident
  // pages its memory cap does not count (`amha tiles` once grew to 3 times its cap that way).
  constexpr std::size_t kMiB = std::size_t{1} << 20;
  setReuseFreedSearchMemory(true);
  const std::size_t live0 = liveLargeBlockBytes();
  {
    ReallocVector<char> big;
    big.resize(64 * kMiB);
    EXPECT_EQ(liveLargeBlockBytes(), live0 + 64 * kMiB);
  }
  EXPECT_EQ(pooledLargeBlockBytes(), 64 * kMiB);
  EXPECT_EQ(liveLargeBlockBytes(), live0);
  {
    ReallocVector<char> small;
    small.resize(8 * kMiB);
    EXPECT_EQ(pooledLargeBlockBytes(), 0u);
    EXPECT_EQ(liveLargeBlockBytes(), live0 + 8 * kMiB) << "the other 56 MiB must be unmapped";
    small.resize(16 * kMiB);  // grows by remapping
    EXPECT_EQ(liveLargeBlockBytes(), live0 + 16 * kMiB);
  }
  EXPECT_EQ(pooledLargeBlockBytes(), 16 * kMiB);

  // The pool keeps at most its limit; lowering the limit unmaps the excess.
  setReuseFreedSearchMemory(true, 20 * kMiB);
  {
    ReallocVector<char> a, b, c;
    a.resize(8 * kMiB);  // a cut of the pooled block
    b.resize(8 * kMiB);
    c.resize(8 * kMiB);
  }
  EXPECT_EQ(pooledLargeBlockBytes(), 16 * kMiB) << "a third 8 MiB block would pass 20 MiB";
  setReuseFreedSearchMemory(true, 4 * kMiB);
  EXPECT_EQ(pooledLargeBlockBytes(), 0u);
  setReuseFreedSearchMemory(false);
  EXPECT_EQ(liveLargeBlockBytes(), live0);
}

TEST(ReallocVector, PoolServesConcurrentSearchesEachTheirOwnBlocks) {
  // Two threads (as in `amha tiles --jobs 2`) take blocks from the pool and give them back.
  setReuseFreedSearchMemory(true);
  auto work = [](std::uint64_t seed, bool* ok) {
    *ok = true;
    for (int round = 0; round < 20; ++round) {
      ReallocVector<std::uint64_t> v;
      const std::size_t n = (kLargeBlockBytes / sizeof(std::uint64_t)) * (1 + round % 3);
      for (std::size_t i = 0; i < n; ++i) v.push_back(seed ^ i);
      for (std::size_t i = 0; i < n; ++i) *ok = *ok && v[i] == (seed ^ i);
    }
  };
  bool ok1 = false, ok2 = false;
  std::thread t1(work, 0x1234u, &ok1), t2(work, 0xABCD0000u, &ok2);
  t1.join();
  t2.join();
  EXPECT_TRUE(ok1);
  EXPECT_TRUE(ok2);
  setReuseFreedSearchMemory(false);
  EXPECT_EQ(pooledLargeBlockBytes(), 0u);
}

TEST(ReallocVector, GrowsLargeBlocksWhenMallocMapsNothing) {
  // What `amha tiles` tells malloc; large arrays must still grow and keep their elements.
  mallopt(M_MMAP_MAX, 0);
  ReallocVector<std::uint32_t> v, other;
  for (std::uint32_t i = 0; i < (1u << 23); ++i) {
    v.push_back(i);
    if (i % 4 == 0) other.push_back(~i);  // interleaved, so that no block sits at the heap top
  }
  for (std::uint32_t i = 0; i < (1u << 23); ++i) ASSERT_EQ(v[i], i) << i;
  for (std::uint32_t i = 0; i < (1u << 21); ++i) ASSERT_EQ(other[i], ~(4 * i)) << i;
  mallopt(M_MMAP_MAX, 65536);  // glibc's default
}

TEST(MapLargeBlocksAlone, RefusesAThresholdMallocCannotHold) {
  // mallopt takes an int: a larger threshold must be refused, not wrapped to a negative one.
  EXPECT_FALSE(mapLargeBlocksAlone(std::size_t{1} << 31));
  EXPECT_FALSE(mapLargeBlocksAlone(std::size_t{1} << 40));
}

}  // namespace
}  // namespace detail
}  // namespace amha
