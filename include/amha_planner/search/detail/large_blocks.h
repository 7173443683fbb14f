// Large blocks for ReallocVector: anonymous mappings grown with mremap, so that growing an
// array of gigabytes remaps its pages instead of copying them (a copy is a pause of seconds
// that no clock check can interrupt), whatever the process has told malloc. Freed blocks are
// unmapped, or kept in a pool for later blocks when setReuseFreedSearchMemory(true).
#pragma once

#include <cstddef>

namespace amha {
namespace detail {

/// Blocks at least this big are mappings; smaller ones stay with malloc (copying them is cheap).
constexpr std::size_t kLargeBlockBytes = std::size_t{4} << 20;

/// A mapping of `bytes` rounded up to whole pages; *mapped receives that size. A pooled block
/// is cut or grown to it. Its contents are unspecified. Throws std::bad_alloc.
void* mapLargeBlock(std::size_t bytes, std::size_t* mapped);

/// Grows a mapping of `mapped` bytes to at least `bytes`, keeping its contents; may move it.
/// *mapped receives the new size. Throws std::bad_alloc (the old mapping is then untouched).
void* growLargeBlock(void* block, std::size_t bytes, std::size_t* mapped);

/// Unmaps the block, or keeps it for reuse.
void releaseLargeBlock(void* block, std::size_t mapped) noexcept;

/// Bytes held in the pool (for tests).
std::size_t pooledLargeBlockBytes();

/// Bytes mapped for blocks in use, i.e. not pooled (for tests).
std::size_t liveLargeBlockBytes();

}  // namespace detail
}  // namespace amha
