// Stacks of 4-byte state ids in 64-byte blocks from one pool with a free list: the storage of
// the bucket queues (bucket_queue.h, key_bucket_queue.h). A stack is the index of its newest
// block (kNone when empty), kept by the caller; each block links to the one below it. A push
// or pop touches one cache line, and a block freed by a pop is reused by the next push that
// needs one, so a warmed-up search allocates nothing.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "amha_planner/search/detail/realloc_vector.h"
#include "amha_planner/search/types.h"

namespace amha {
namespace detail {

class IdStacks {
 public:
  static constexpr std::uint32_t kNone = 0xffffffffu;

  /// Pushes id on the stack whose newest block is head, updating head when it takes a block.
  void push(std::uint32_t& head, StateId id) {
    if (head == kNone || blocks_[head].count == kIds) {
      const std::uint32_t nb = newBlock();
      blocks_[nb].next = head;
      head = nb;
    }
    Block& b = blocks_[head];
    b.ids[b.count++] = id;
  }
  /// True if push() onto this stack allocates nothing (its newest block has room).
  bool hasRoom(std::uint32_t head) const { return head != kNone && blocks_[head].count < kIds; }

  /// The newest id of a non-empty stack.
  StateId top(std::uint32_t head) const {
    const Block& b = blocks_[head];
    return b.ids[b.count - 1];
  }
  /// Pops a non-empty stack; head becomes kNone when it empties.
  void pop(std::uint32_t& head) {
    Block& b = blocks_[head];
    if (--b.count == 0) {
      const std::uint32_t freed = head;
      head = b.next;
      b.next = free_;
      free_ = freed;
    }
  }

  /// Forgets every stack; the memory stays for reuse.
  void clear() {
    blocks_.clear();
    free_ = kNone;
  }

  /// Calls fn(id) for every id of the stack.
  template <typename F>
  void forEach(std::uint32_t head, F&& fn) const {
    for (std::uint32_t bi = head; bi != kNone; bi = blocks_[bi].next) {
      const Block& b = blocks_[bi];
      for (std::uint32_t j = 0; j < b.count; ++j) fn(b.ids[j]);
    }
  }

  std::size_t memoryBytes() const { return blocks_.capacity() * sizeof(Block); }
  /// Bytes a push that needs a new block may allocate (0 while a freed block or room is left).
  std::size_t newBlockBytes() const {
    if (free_ != kNone || blocks_.size() < blocks_.capacity()) return 0;
    return std::max<std::size_t>(blocks_.capacity(), 1) * sizeof(Block);
  }

 private:
  static constexpr std::uint32_t kIds = 14;
  struct Block {
    std::uint32_t next;   // the block below it in its stack, or kNone
    std::uint32_t count;  // ids in use; the newest is ids[count - 1]
    std::uint32_t ids[kIds];
  };
  static_assert(sizeof(Block) == 64, "one block per cache line");

  std::uint32_t newBlock() {
    std::uint32_t b = free_;
    if (b != kNone) {
      free_ = blocks_[b].next;
    } else {
      b = static_cast<std::uint32_t>(blocks_.size());
      blocks_.resize(blocks_.size() + 1);
    }
    blocks_[b].count = 0;
    return b;
  }

  ReallocVector<Block> blocks_;
  std::uint32_t free_ = kNone;  // free blocks, linked through next
};

}  // namespace detail
}  // namespace amha
