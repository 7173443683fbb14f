#include "amha_planner/tiles/tiles_problem.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <stdexcept>

#include "line_conflict.h"

namespace amha {
namespace tiles {

namespace {

// Per-state word: MD (10 bits; at most 720 on 9x9), LC/2 (8 bits; at most 144), MT (7 bits),
// blank position (7 bits).
constexpr std::uint32_t packInfo(int md, int lc_half, int mt, int blank) {
  return static_cast<std::uint32_t>(md) | static_cast<std::uint32_t>(lc_half) << 10 |
         static_cast<std::uint32_t>(mt) << 18 | static_cast<std::uint32_t>(blank) << 25;
}
constexpr int infoMd(std::uint32_t i) { return static_cast<int>(i & 1023u); }
constexpr int infoLcHalf(std::uint32_t i) { return static_cast<int>((i >> 10) & 255u); }
constexpr int infoMt(std::uint32_t i) { return static_cast<int>((i >> 18) & 127u); }
constexpr int infoBlank(std::uint32_t i) { return static_cast<int>(i >> 25); }

// The N x N puzzle: B bits a tile, W 64-bit words a board. N is a template parameter so that
// divisions by N compile to multiplications and the per-tile loops unroll.
template <int N>
class TilesSpace final : public TilesProblem {
 public:
  static constexpr int B = N <= 4 ? 4 : N == 5 ? 5 : N <= 8 ? 6 : 7;
  static constexpr int W = (N * N * B + 63) / 64;

  TilesSpace(const Board& start, std::vector<TermWeights> weights)
      : TilesProblem(start.size, std::move(weights)) {
    for (int p = 0; p < n2_; ++p) {
      const int r = p / n_, c = p % n_;
      int k = 0;
      if (r > 0) neighbours_[p][k++] = static_cast<std::uint8_t>(p - n_);
      if (r < n_ - 1) neighbours_[p][k++] = static_cast<std::uint8_t>(p + n_);
      if (c > 0) neighbours_[p][k++] = static_cast<std::uint8_t>(p - 1);
      if (c < n_ - 1) neighbours_[p][k++] = static_cast<std::uint8_t>(p + 1);
      num_neighbours_[p] = static_cast<std::uint8_t>(k);
    }
    for (int p = 0; p < n2_; ++p) {
      for (int k = 0; k < num_neighbours_[p]; ++k) {
        const int q = neighbours_[p][k];
        for (int j = 0; j < num_neighbours_[q]; ++j) {
          if (neighbours_[q][j] == p) back_[p][k] = static_cast<std::uint8_t>(j);
        }
      }
    }
    for (int p = 0; p < n2_; ++p) {
      const int r = p / n_, c = p % n_;
      for (int t = 0; t < n2_; ++t) {
        dist_[t * n2_ + p] = static_cast<std::uint8_t>(std::abs(r - t / n_) + std::abs(c - t % n_));
      }
    }
    setTableSize(12);
    const Board goal = goalBoard(n_);
    start_ = insertBoard(start);
    goal_ = insertBoard(goal);
  }

  StateId start() const override { return start_; }
  StateId goal() const override { return goal_; }
  std::size_t numStates() const override { return count_; }

  void successors(StateId s, std::vector<Edge>& out) override {
    out.clear();
    std::uint64_t parent[W];
    std::memcpy(parent, words(s), sizeof(parent));
    const std::uint32_t info = infoOf(s);
    const int b = infoBlank(info);
    const int n = num_neighbours_[b];
    // The child that undoes the move which created s is the state s was created from: its id
    // is stored with s, which saves a table lookup and a read of its board for about a third
    // of all children (the two most likely cache misses of an expansion).
    const std::uint32_t from = fromOf(s);
    const int from_k = from == kNoFrom ? -1 : static_cast<int>(from >> kFromIdBits);
    // Three passes over the other children so that their cache misses overlap: make the
    // boards and prefetch their table slots; prefetch the stored board a slot's tag points
    // to; then look up and insert as usual (the prefetches are only hints).
    std::uint64_t child[4][W];
    std::uint64_t hash[4];
    int tile[4];
    for (int k = 0; k < n; ++k) {
      if (k == from_k) continue;
      tile[k] = makeChild(parent, b, neighbours_[b][k], child[k]);
      hash[k] = hashWords(child[k]);
      __builtin_prefetch(&slots_[hash[k] & mask_]);
    }
    // The next expansion is often a child of s whose move brought its tile closer to the tile's
    // goal (MD falls, and every heuristic weighs MD): prefetch the table slots of those
    // children's own children now, so that the next expansion's slot misses overlap with this
    // one's work instead of stalling it (the stall on the slots fell from 38 % to 13 % of
    // successors() on Korf's 15-puzzles).
    for (int k = 0; k < n; ++k) {
      if (k == from_k) continue;
      const int p = neighbours_[b][k];
      if (dist_[tile[k] * n2_ + b] >= dist_[tile[k] * n2_ + p]) continue;
      for (int j = 0; j < num_neighbours_[p]; ++j) {
        const int q = neighbours_[p][j];
        if (q == b) continue;
        std::uint64_t grandchild[W];
        makeChild(child[k], p, q, grandchild);
        __builtin_prefetch(&slots_[hashWords(grandchild) & mask_]);
      }
    }
    for (int k = 0; k < n; ++k) {
      if (k == from_k) continue;
      const std::uint32_t tag = tagOf(hash[k]);
      for (std::size_t slot = hash[k] & mask_;; slot = (slot + 1) & mask_) {
        const std::uint32_t v = slots_[slot];
        if (v == kEmpty) break;
        if ((v & ~id_mask_) == tag) {
          __builtin_prefetch(words(v & id_mask_));
          break;
        }
      }
    }
    for (int k = 0; k < n; ++k) {
      if (k == from_k) {
        out.push_back(Edge{from & kFromIdMask, 1});
        continue;
      }
      std::size_t slot;
      StateId id = probe(child[k], hash[k], &slot);
      if (id == kEmpty) {
        const int p = neighbours_[b][k];
        id = insertAt(slot, hash[k], child[k], childInfo(parent, info, b, p, tile[k]),
                      linkFrom(s, b, k));
      }
      out.push_back(Edge{id, 1});
    }
  }

  void heuristics(StateId s, HeuristicValue* h, std::size_t count) override {
    const HeuristicTerms t = terms(s);
    if (count > 0) h[0] = anchorValue(t);
    for (std::size_t i = 1; i < count; ++i) h[i] = weightedValue(t, weights_[i - 1]);
  }

  Board board(StateId s) const override {
    Board b;
    b.size = n_;
    b.tiles.resize(static_cast<std::size_t>(n2_));
    unpack(words(s), b.tiles.data());
    return b;
  }

  HeuristicTerms terms(StateId s) const override {
    const std::uint32_t i = infoOf(s);
    return HeuristicTerms{infoMd(i), 2 * infoLcHalf(i), infoMt(i)};
  }

  std::size_t arenaBytes() const override {
    return chunks_.size() * kChunkStates * (sizeof(std::uint64_t) * W + 2 * sizeof(std::uint32_t)) +
           chunks_.capacity() * sizeof(Chunk);
  }
  std::size_t tableBytes() const override { return slots_.capacity() * sizeof(StateId); }

 private:
  static constexpr StateId kEmpty = 0xFFFFFFFFu;
  static constexpr int kChunkBits = 18;
  static constexpr std::size_t kChunkStates = std::size_t{1} << kChunkBits;
  static constexpr std::uint64_t kFieldMask = (std::uint64_t{1} << B) - 1;

  // Chunks of 2^18 boards never move, so growing the arena copies nothing. Left
  // uninitialised: insertAt writes every slot before it is read.
  struct Chunk {
    std::unique_ptr<std::uint64_t[]> words;
    std::unique_ptr<std::uint32_t[]> info;
    std::unique_ptr<std::uint32_t[]> from;  // see fromOf()
  };

  const std::uint64_t* words(StateId s) const {
    return chunks_[s >> kChunkBits].words.get() + (s & (kChunkStates - 1)) * W;
  }
  std::uint32_t infoOf(StateId s) const {
    return chunks_[s >> kChunkBits].info[s & (kChunkStates - 1)];
  }
  // The state a board was first created from: its id (low 30 bits) and, in the top 2 bits,
  // which of the board's blank moves leads back to it; kNoFrom for the start and goal (and
  // for ids too large to fit, which then take the ordinary lookup).
  static constexpr std::uint32_t kNoFrom = 0xFFFFFFFFu;
  static constexpr int kFromIdBits = 30;
  static constexpr std::uint32_t kFromIdMask = (1u << kFromIdBits) - 1;
  std::uint32_t fromOf(StateId s) const {
    return chunks_[s >> kChunkBits].from[s & (kChunkStates - 1)];
  }
  // Link for the child of s (blank at b) made by moving the tile at b's k-th neighbour.
  std::uint32_t linkFrom(StateId s, int b, int k) const {
    if (s >= kFromIdMask) return kNoFrom;
    return s | static_cast<std::uint32_t>(back_[b][k]) << kFromIdBits;
  }

  static std::uint32_t getField(const std::uint64_t* w, int i) {
    const int bit = i * B, wi = bit >> 6, off = bit & 63;
    std::uint64_t v = w[wi] >> off;
    if (off + B > 64) v |= w[wi + 1] << (64 - off);
    return static_cast<std::uint32_t>(v & kFieldMask);
  }
  static void setField(std::uint64_t* w, int i, std::uint32_t val) {
    const int bit = i * B, wi = bit >> 6, off = bit & 63;
    w[wi] = (w[wi] & ~(kFieldMask << off)) | (static_cast<std::uint64_t>(val) << off);
    if (off + B > 64) {
      const int spill = off + B - 64;  // bits in the next word
      const std::uint64_t m = (std::uint64_t{1} << spill) - 1;
      w[wi + 1] = (w[wi + 1] & ~m) | (static_cast<std::uint64_t>(val) >> (64 - off));
    }
  }
  static void xorField(std::uint64_t* w, int i, std::uint64_t val) {
    const int bit = i * B, wi = bit >> 6, off = bit & 63;
    w[wi] ^= val << off;
    if (off + B > 64) w[wi + 1] ^= val >> (64 - off);
  }
  void unpack(const std::uint64_t* w, std::uint8_t* tiles) const {
    for (int i = 0; i < n2_; ++i) tiles[i] = static_cast<std::uint8_t>(getField(w, i));
  }

  // The board made by moving the tile at p into the blank at b; returns that tile. Field b
  // holds 0 and field p holds t: XOR-ing t into both moves the tile.
  static int makeChild(const std::uint64_t* parent, int b, int p, std::uint64_t* child) {
    const std::uint32_t t = getField(parent, p);
    std::memcpy(child, parent, sizeof(std::uint64_t) * W);
    xorField(child, b, t);
    xorField(child, p, t);
    return static_cast<int>(t);
  }

  static std::uint64_t hashWords(const std::uint64_t* w) {
    std::uint64_t h = 0x9E3779B97F4A7C15ull;
    for (int i = 0; i < W; ++i) {
      h = (h ^ w[i]) * 0xff51afd7ed558ccdull;
      h ^= h >> 32;
    }
    h *= 0xc4ceb9fe1a85ec53ull;
    h ^= h >> 29;
    return h;
  }

  // MD, LC and MT of the child reached by moving tile t from p into the blank at b, from the
  // parent's values and packed board.
  std::uint32_t childInfo(const std::uint64_t* parent, std::uint32_t info, int b, int p,
                          int t) const {
    const int md = infoMd(info) + dist_[t * n2_ + b] - dist_[t * n2_ + p];
    const int mt = infoMt(info) + (t != b) - (t != p);
    int lc_half = infoLcHalf(info);
    // A horizontal move keeps the order of the tiles within the row; it changes the contents
    // of columns col(p) and col(b), and only t's goal column can gain or lose a tile that
    // belongs in it (vertical moves: the same with rows and columns swapped). Both boards hold
    // t or the blank at the same offset of that line, and agree on the rest of it.
    const bool horizontal = (b / N) == (p / N);
    const int goal_line = horizontal ? t % N : t / N;
    const int from_line = horizontal ? p % N : p / N;
    const int to_line = horizontal ? b % N : b / N;
    if (goal_line == from_line || goal_line == to_line) {
      const bool row = !horizontal;               // the changed line is a row for vertical moves
      const int at = horizontal ? p / N : p % N;  // offset of t (or the blank) in that line
      auto get = [&](int k) {
        return static_cast<int>(getField(parent, row ? goal_line * N + k : k * N + goal_line));
      };
      const int added = detail::lineRemovalsAddedTile<N>(get, row, goal_line, at, t);
      lc_half += goal_line == to_line ? added : -added;
    }
    return packInfo(md, lc_half, mt, p);
  }

  StateId insertBoard(const Board& b) {
    std::uint64_t w[W] = {};
    for (int i = 0; i < n2_; ++i) setField(w, i, b.tiles[i]);
    const std::uint64_t h = hashWords(w);
    std::size_t slot;
    const StateId id = probe(w, h, &slot);
    if (id != kEmpty) return id;
    const HeuristicTerms t = heuristicTerms(b);
    return insertAt(slot, h, w, packInfo(t.md, t.lc / 2, t.mt, blankPosition(b)), kNoFrom);
  }

  // Table slots: the low shift_ bits hold the id (ids stay below 0.9 * capacity = 0.9 *
  // 2^shift_), the high 32 - shift_ bits a tag taken from the top of the hash, so that probes
  // past other states rarely read the arena. All ones (kEmpty) is never a stored value.
  void setTableSize(int shift) {
    setShift(shift);
    slots_.assign(std::size_t{1} << shift, kEmpty);
  }
  void setShift(int shift) {
    shift_ = shift;
    mask_ = (std::size_t{1} << shift) - 1;
    id_mask_ = static_cast<std::uint32_t>(mask_);
  }
  static std::uint32_t tagOf(std::uint64_t h, int shift) {
    return static_cast<std::uint32_t>(h >> (32 + shift)) << shift;
  }
  std::uint32_t tagOf(std::uint64_t h) const { return tagOf(h, shift_); }
  // The id of board w (hash h), or kEmpty and the free slot where it belongs.
  StateId probe(const std::uint64_t* w, std::uint64_t h, std::size_t* slot_out) const {
    const std::uint32_t tag = tagOf(h);
    std::size_t slot = h & mask_;
    for (;; slot = (slot + 1) & mask_) {
      const std::uint32_t v = slots_[slot];
      if (v == kEmpty) break;
      if ((v & ~id_mask_) == tag &&
          std::memcmp(words(v & id_mask_), w, sizeof(std::uint64_t) * W) == 0) {
        *slot_out = slot;
        return v & id_mask_;
      }
    }
    *slot_out = slot;
    return kEmpty;
  }

  StateId insertAt(std::size_t slot, std::uint64_t h, const std::uint64_t* w, std::uint32_t info,
                   std::uint32_t from) {
    const StateId id = static_cast<StateId>(count_);
    if ((count_ & (kChunkStates - 1)) == 0) {
      Chunk c;
      c.words.reset(new std::uint64_t[kChunkStates * W]);
      c.info.reset(new std::uint32_t[kChunkStates]);
      c.from.reset(new std::uint32_t[kChunkStates]);
      chunks_.push_back(std::move(c));
    }
    Chunk& c = chunks_.back();
    const std::size_t off = count_ & (kChunkStates - 1);
    std::memcpy(c.words.get() + off * W, w, sizeof(std::uint64_t) * W);
    c.info[off] = info;
    c.from[off] = from;
    ++count_;
    slots_[slot] = tagOf(h) | id;
    if (count_ * 10 > slots_.size() * 7 && count_ >= retry_growth_at_) {
      // Past 90 % full, linear probing degrades fast: then the table grows whatever the search's
      // limits say. Below, a rebuild the search's limits cut short is retried 1/32 later.
      const bool must = count_ * 10 > slots_.size() * 9;
      if (!growTable(!must)) retry_growth_at_ = count_ + slots_.size() / 32;
    }
    return id;
  }

  void setInterruptCheck(std::function<bool()> check) override { interrupted_ = std::move(check); }

  // Doubles the table: false if the search's limit check stopped the rebuild (only when
  // may_give_up), the old table then staying in place. At tens of millions of states a rebuild
  // takes seconds (1.65 s at 47 M states), which a time limit or a cancel should not wait for.
  bool growTable(bool may_give_up) {
    auto give_up = [&] { return may_give_up && interrupted_ && interrupted_(); };
    if (give_up()) return false;  // before allocating: the search is stopping anyway
    const int shift = shift_ + 1;
    if (shift > 31) throw std::length_error("sliding tiles: more than 1.5 billion states");
    const std::size_t mask = (std::size_t{1} << shift) - 1;
    std::vector<std::uint32_t> fresh(mask + 1, kEmpty);
    // Walk the arena in id order (sequential reads) rather than the old table (random reads).
    // The writes land at random: hash kAhead states ahead and prefetch their slots, so that
    // the misses overlap (this loop was a fifth of successors() on Korf's 15-puzzles).
    constexpr std::size_t kAhead = 16;
    std::uint64_t ring[kAhead];
    const std::size_t n = count_;
    for (std::size_t id = 0; id < std::min(n, kAhead); ++id) {
      ring[id] = hashWords(words(static_cast<StateId>(id)));
      __builtin_prefetch(&fresh[ring[id] & mask], 1);
    }
    for (std::size_t id = 0; id < n; ++id) {
      if ((id & 0xFFFF) == 0xFFFF && give_up()) return false;  // every 2^16 states, ~2 ms
      const std::uint64_t h = ring[id % kAhead];
      if (id + kAhead < n) {
        const std::uint64_t ahead = hashWords(words(static_cast<StateId>(id + kAhead)));
        ring[id % kAhead] = ahead;
        __builtin_prefetch(&fresh[ahead & mask], 1);
      }
      std::size_t slot = h & mask;
      while (fresh[slot] != kEmpty) slot = (slot + 1) & mask;
      fresh[slot] = tagOf(h, shift) | static_cast<StateId>(id);
    }
    slots_.swap(fresh);
    setShift(shift);
    return true;
  }

  static constexpr int n_ = N, n2_ = N * N;
  StateId start_ = 0, goal_ = 0;
  std::size_t count_ = 0;
  std::vector<Chunk> chunks_;
  std::vector<std::uint32_t> slots_;
  std::size_t retry_growth_at_ = 0;    // no table growth before this many states
  std::function<bool()> interrupted_;  // the running search's limit check, if any
  std::size_t mask_ = 0;
  std::uint32_t id_mask_ = 0;
  int shift_ = 0;
  std::uint8_t neighbours_[N * N][4] = {};
  std::uint8_t num_neighbours_[N * N] = {};
  std::uint8_t back_[N * N][4] =
      {};  // back_[b][k]: index of b among neighbours_[neighbours_[b][k]]
  std::uint8_t dist_[N * N * N * N] = {};  // dist_[t * N * N + p]: Manhattan distance
};

}  // namespace

std::unique_ptr<TilesProblem> TilesProblem::create(const Board& start,
                                                   std::vector<TermWeights> weights) {
  const std::string err = boardError(start);
  if (!err.empty()) throw std::invalid_argument("invalid start board: " + err);
  if (!isSolvable(start)) {
    throw std::invalid_argument("unsolvable start board: " + toString(start));
  }
  for (const TermWeights& w : weights) {
    if (!(w.md >= 0 && w.lc >= 0 && w.mt >= 0) || w.md > 1e6 || w.lc > 1e6 || w.mt > 1e6) {
      throw std::invalid_argument("heuristic weights must be finite, >= 0 and <= 1e6");
    }
  }
  switch (start.size) {
    case 3:
      return std::make_unique<TilesSpace<3>>(start, std::move(weights));
    case 4:
      return std::make_unique<TilesSpace<4>>(start, std::move(weights));
    case 5:
      return std::make_unique<TilesSpace<5>>(start, std::move(weights));
    case 6:
      return std::make_unique<TilesSpace<6>>(start, std::move(weights));
    case 7:
      return std::make_unique<TilesSpace<7>>(start, std::move(weights));
    case 8:
      return std::make_unique<TilesSpace<8>>(start, std::move(weights));
    default:
      return std::make_unique<TilesSpace<9>>(start, std::move(weights));
  }
}

}  // namespace tiles
}  // namespace amha
