#include "amha_planner/search/detail/large_blocks.h"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <mutex>
#include <new>
#include <utility>
#include <vector>

#include "amha_planner/search/detail/memory_reuse.h"

#if defined(__SANITIZE_THREAD__)
#define AMHA_UNDER_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define AMHA_UNDER_TSAN 1
#endif
#endif
#ifndef AMHA_UNDER_TSAN
#define AMHA_UNDER_TSAN 0
#endif

namespace amha {
namespace detail {
namespace {

std::atomic<bool> g_reuse{false};

std::atomic<std::size_t> g_max_pooled{0};
std::atomic<std::size_t> g_live{0};  // bytes mapped for blocks in use (not pooled)

struct Pool {
  std::mutex mutex;
  std::vector<std::pair<void*, std::size_t>> blocks;  // (mapping, size)
  std::size_t pooled = 0;                             // their sizes' sum
};

Pool& pool() {
  static Pool* p = new Pool;  // never destroyed: blocks may be released during static teardown
  return *p;
}

std::size_t roundToPages(std::size_t bytes) {
  static const std::size_t page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  if (bytes > static_cast<std::size_t>(-1) - page) throw std::bad_alloc();
  return (bytes + page - 1) / page * page;
}

// A pooled block for `bytes`: the smallest that is big enough, else the largest (to be grown).
bool takePooled(std::size_t bytes, void** block, std::size_t* mapped) {
  Pool& p = pool();
  std::lock_guard<std::mutex> lock(p.mutex);
  if (p.blocks.empty()) return false;
  auto best = p.blocks.end();
  for (auto it = p.blocks.begin(); it != p.blocks.end(); ++it) {
    if (it->second >= bytes && (best == p.blocks.end() || it->second < best->second)) best = it;
  }
  if (best == p.blocks.end()) {
    best = std::max_element(p.blocks.begin(), p.blocks.end(),
                            [](const auto& a, const auto& b) { return a.second < b.second; });
  }
  *block = best->first;
  *mapped = best->second;
  p.pooled -= best->second;
  p.blocks.erase(best);
  return true;
}

}  // namespace

void* mapLargeBlock(std::size_t bytes, std::size_t* mapped) {
  bytes = roundToPages(bytes);
  void* block = nullptr;
  std::size_t size = 0;
  if (takePooled(bytes, &block, &size)) {
    if (size > bytes) {
      // Unmap the tail: the caller's memory cap counts `bytes`, and a small array must not
      // keep a big array's resident pages (that let `amha tiles` reach 3 times its cap).
      munmap(static_cast<char*>(block) + bytes, size - bytes);
      size = bytes;
    }
    g_live += size;
    if (size == bytes) {
      *mapped = size;
      return block;
    }
    try {
      void* grown = growLargeBlock(block, bytes, &size);
      *mapped = size;
      return grown;
    } catch (const std::bad_alloc&) {
      releaseLargeBlock(block, size);
      throw;
    }
  }
  block = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (block == MAP_FAILED) throw std::bad_alloc();
  g_live += bytes;
  *mapped = bytes;
  return block;
}

void* growLargeBlock(void* block, std::size_t bytes, std::size_t* mapped) {
  bytes = roundToPages(bytes);
  if (bytes <= *mapped) return block;
#if AMHA_UNDER_TSAN
  // ThreadSanitizer does not intercept mremap: the range a block leaves keeps its writers'
  // history, and a later mapping there (another thread's) is reported as a race. Under TSan
  // only, grow by copying through calls it does see.
  void* moved = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (moved == MAP_FAILED) throw std::bad_alloc();
  std::memcpy(moved, block, *mapped);
  munmap(block, *mapped);
#else
  void* moved = mremap(block, *mapped, bytes, MREMAP_MAYMOVE);
  if (moved == MAP_FAILED) throw std::bad_alloc();
#endif
  g_live += bytes - *mapped;
  *mapped = bytes;
  return moved;
}

void releaseLargeBlock(void* block, std::size_t mapped) noexcept {
  if (block == nullptr) return;
  g_live -= mapped;
  if (g_reuse.load(std::memory_order_relaxed)) {
    Pool& p = pool();
    std::lock_guard<std::mutex> lock(p.mutex);
    if (p.pooled + mapped <= g_max_pooled.load(std::memory_order_relaxed)) {
      try {
        p.blocks.emplace_back(block, mapped);
        p.pooled += mapped;
        return;
      } catch (const std::bad_alloc&) {
        // no room to remember it: unmap it instead
      }
    }
  }
  munmap(block, mapped);
}

std::size_t pooledLargeBlockBytes() {
  Pool& p = pool();
  std::lock_guard<std::mutex> lock(p.mutex);
  return p.pooled;
}

std::size_t liveLargeBlockBytes() { return g_live.load(); }

}  // namespace detail

void setReuseFreedSearchMemory(bool reuse, std::size_t max_pooled_bytes) {
  detail::g_max_pooled.store(max_pooled_bytes, std::memory_order_relaxed);
  detail::g_reuse.store(reuse, std::memory_order_relaxed);
  // Turning reuse off returns what the pool holds; a lower limit returns the excess.
  detail::Pool& p = detail::pool();
  std::lock_guard<std::mutex> lock(p.mutex);
  const std::size_t keep = reuse ? max_pooled_bytes : 0;
  while (p.pooled > keep) {
    munmap(p.blocks.back().first, p.blocks.back().second);
    p.pooled -= p.blocks.back().second;
    p.blocks.pop_back();
  }
}

}  // namespace amha
