// The engine's per-state data: one record per state (array of structs), so that touching a
// state costs one or two cache misses instead of one per array. MhaEngine reads and writes it
// through the accessors below and keeps only the algorithm.
//
// Record layout in 32-bit words:
//   [0..1] kInfiniteCost - g (int64)  [2] ~parent  [3] flags  [4 .. 4+nh) h_i
//   [4+nh .. 4+2nh) the inflation bases b_i, if the problem has them (hw = 2 nh, else nh)
//   [4+hw .. 4+hw+mw) membership bits: bit i set <=> the state is in OPEN_i; with at most 28
//   queues mw = 0 and they are bits 4 + i of the flags word
// padded to an even stride so that g stays 8-byte aligned. g and parent are stored so that a
// new state's record (g = infinity, no parent, nothing set) is all zero bits: the records
// then need no initialising, and their pages no touching, until a state is generated.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "amha_planner/search/detail/realloc_vector.h"
#include "amha_planner/search/types.h"

namespace amha {
namespace detail {

class StateRecords {
 public:
  // kIncons marks the INCONS list: closed by the anchor, g lowered since (no separate list).
  // kStaleH: the cached heuristics predate SearchProblem::upgradeHeuristics (lower bounds of
  // the new ones); the next generate() recomputes them.
  enum Flag : std::uint32_t {
    kGenerated = 1,
    kClosedAnch = 2,
    kClosedInad = 4,
    kIncons = 8,
    kStaleH = 16
  };

  /// Lays the records out for `nh` heuristics (anchor included), with inflation bases or not.
  /// False (and nothing changes) if that is the current layout; true if it changed: every
  /// record is then dropped.
  bool configure(std::size_t nh, bool bases) {
    if (nh == nh_ && bases == bases_) return false;
    nh_ = nh;
    bases_ = bases;
    hw_ = nh_ * (bases_ ? 2 : 1);
    member_words_ = nh_ <= kFlagMembers ? 0 : (nh_ + 31) / 32;
    member_word_ = member_words_ == 0 ? 3 : kHeaderWords + hw_;
    member_shift_ = member_words_ == 0 ? kFlagBits : 0;
    stride_ = kHeaderWords + hw_ + member_words_;
    stride_ += stride_ % 2;
    rec_.clear();
    return true;
  }
  std::size_t heuristics() const { return nh_; }
  bool hasBases() const { return bases_; }

  /// Room for `cap` records (exactly: resize() alone would double, past the memory cap). New
  /// records are not written here but by zero() when their ids come into use.
  void reserve(std::size_t cap) {
    rec_.reserve(cap * stride_);
    rec_.resize(cap * stride_);
  }
  /// Sets records [from, to) to all zero: g = infinity, no parent, no flags, in no queue.
  void zero(std::size_t from, std::size_t to) {
    if (to > from)
      std::memset(rec(static_cast<StateId>(from)), 0,
                  (to - from) * stride_ * sizeof(std::uint32_t));
  }
  std::size_t bytes() const { return rec_.capacity() * sizeof(std::uint32_t); }

  Cost g(StateId s) const {
    Cost v;
    std::memcpy(&v, rec(s), sizeof v);
    return kInfiniteCost - v;
  }
  void setG(StateId s, Cost g) {
    const Cost v = kInfiniteCost - g;
    std::memcpy(rec(s), &v, sizeof v);
  }
  StateId parent(StateId s) const { return ~rec(s)[2]; }
  void setParent(StateId s, StateId p) { rec(s)[2] = ~p; }
  std::uint32_t& flags(StateId s) { return rec(s)[3]; }
  std::uint32_t flags(StateId s) const { return rec(s)[3]; }
  HeuristicValue h(StateId s, std::size_t i) const { return rec(s)[kHeaderWords + i]; }
  HeuristicValue base(StateId s, std::size_t i) const { return rec(s)[kHeaderWords + nh_ + i]; }
  /// Where the problem writes a new state's h_i, and its b_i (with bases).
  std::uint32_t* heuristicsOut(StateId s) { return rec(s) + kHeaderWords; }
  std::uint32_t* basesOut(StateId s) { return rec(s) + kHeaderWords + nh_; }

  // Queue membership. Up to kFlagMembers queues keep their bits in the flags word, above the
  // flags (a word less per record); more have words of their own after the heuristic values.
  // Queue i's bit is bit (i + member_shift_) % 32 of word member_word_ + (i + member_shift_) / 32.
  bool inOpen(StateId s, std::size_t i) const { return (memberWord(s, i) & memberBit(i)) != 0; }
  void setInOpen(StateId s, std::size_t i) { memberWord(s, i) |= memberBit(i); }
  void clearInOpen(StateId s, std::size_t i) { memberWord(s, i) &= ~memberBit(i); }
  void clearAllOpen(StateId s) {
    if (member_words_ == 0) {
      rec(s)[3] &= (1u << kFlagBits) - 1;
      return;
    }
    std::uint32_t* m = rec(s) + kHeaderWords + hw_;
    for (std::size_t w = 0; w < member_words_; ++w) m[w] = 0;
  }

  /// Starts loading a record into the cache (for_write: it will be written).
  void prefetch(StateId s, bool for_write = false) const {
    const std::uint32_t* r = rec(s);
    if (for_write) {
      __builtin_prefetch(r, 1);
    } else {
      __builtin_prefetch(r);
      __builtin_prefetch(r + stride_ - 1);  // a record can straddle two cache lines
    }
  }

 private:
  static constexpr std::size_t kHeaderWords = 4;
  static constexpr std::size_t kFlagBits = 5, kFlagMembers = 32 - kFlagBits;

  std::uint32_t* rec(StateId s) { return rec_.data() + static_cast<std::size_t>(s) * stride_; }
  const std::uint32_t* rec(StateId s) const {
    return rec_.data() + static_cast<std::size_t>(s) * stride_;
  }
  std::uint32_t& memberWord(StateId s, std::size_t i) {
    return rec(s)[member_word_ + (i + member_shift_) / 32];
  }
  std::uint32_t memberWord(StateId s, std::size_t i) const {
    return rec(s)[member_word_ + (i + member_shift_) / 32];
  }
  std::uint32_t memberBit(std::size_t i) const { return 1u << ((i + member_shift_) % 32); }

  std::size_t nh_ = 0;            // heuristics in use, anchor included (0: not laid out yet)
  bool bases_ = false;            // SearchProblem::hasInflationBases: b_i after the h_i
  std::size_t hw_ = 1;            // record words of heuristic values: nh_, 2 nh_ with bases
  std::size_t member_words_ = 1;  // words of membership bits per record (0: in the flags word)
  std::size_t member_word_ = kHeaderWords + 1, member_shift_ = 0;  // where they are (memberWord)
  std::size_t stride_ = kHeaderWords + 2;
  ReallocVector<std::uint32_t> rec_;
};

}  // namespace detail
}  // namespace amha
