// Distance grids from the goal with a bucket queue or a radix heap, several in parallel.
#include "amha_planner/lattice/detail/heuristic_grids.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <queue>
#include <thread>
#include <utility>

#include "amha_planner/lattice/lattice_graph.h"
#include "dial_queue.h"
#include "distance_repair.h"
#include "radix_heap.h"

namespace amha {
namespace lattice {

namespace {

// Distances are stored atomically: a search may read a grid that a background thread still
// completes (GridProgress). Relaxed: the order comes from GridProgress::final_bits. Encoded
// (encodeDistance): `dist` below always points to a grid's stored cells.
inline void storeDistance(std::uint32_t* dist, std::size_t i, std::uint32_t v) {
  __atomic_store_n(dist + i, encodeDistance(v), __ATOMIC_RELAXED);
}

/// Spins, then yields: the helper works on another core and a search waits for it a few
/// microseconds at a time, far below a sleep's granularity (sleeping 50 us made proofs on the
/// Willow Garage map 10-40 % slower); yielding leaves the core to the helper on a busy machine.
void pause(unsigned& spins) {
  if (++spins < 256) {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
    return;
  }
  std::this_thread::yield();
}

}  // namespace

std::uint32_t GridProgress::read(const std::uint32_t* stored, std::size_t i) const {
  for (unsigned spins = 0;;) {
    // Complete: a cell without its bit was never reached (kUnreachable).
    if (isFinal(i) || complete.load(std::memory_order_acquire))
      return decodeDistance(__atomic_load_n(stored + i, __ATOMIC_RELAXED));
    if (abandoned.load(std::memory_order_acquire)) return boundBeyond(direction.atIndex(i));
    pause(spins);
  }
}

bool GridProgress::waitComplete() const {
  for (unsigned spins = 0;;) {
    if (complete.load(std::memory_order_acquire)) return true;
    if (abandoned.load(std::memory_order_acquire)) return false;
    pause(spins);
  }
}

/// One compute() or repair(): its tasks (-1: the block abstraction; k: grid kind k), taken in
/// order by the threads that work on it. Shared with the background threads, which may outlive
/// the call.
struct HeuristicGridBuilder::Job {
  int gx = 0, gy = 0, gh = 0;
  bool backward = false;
  std::vector<int> tasks;
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stopped{false};  // a task was stopped: the job's result is void
  std::atomic<bool> cancel{false};   // stops the background threads
  StopCondition background_stop{&cancel, std::numeric_limits<double>::infinity()};
  std::shared_ptr<const GoalHeuristics> old;       // repair() only
  const std::vector<CellRect>* changed = nullptr;  // repair() only
  const DistanceGrid* base[kNumGridKinds] = {nullptr, nullptr, nullptr, nullptr};
  std::shared_ptr<DistanceGrid> result[kNumGridKinds];
  GoalHeuristics* out = nullptr;  // the abstraction's task writes it (never a background one)
};

HeuristicGridBuilder::~HeuristicGridBuilder() { reapBackground(true); }

void HeuristicGridBuilder::reapBackground(bool all) const {
  std::lock_guard<std::mutex> lock(background_mutex_);
  if (all) {
    for (Background& b : background_) {
      if (const std::shared_ptr<Job> job = b.job.lock())
        job->cancel.store(true, std::memory_order_relaxed);
    }
  }
  for (auto it = background_.begin(); it != background_.end();) {
    if (all || it->done.load(std::memory_order_acquire)) {
      it->thread.join();
      it = background_.erase(it);
    } else {
      ++it;
    }
  }
}

std::vector<std::uint32_t> DistanceGrid::distances() const {
  std::vector<std::uint32_t> out(stored.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = decodeDistance(stored[i]);
  return out;
}

std::size_t GoalHeuristics::bytes() const {
  std::size_t b = sizeof(*this) + coarse.capacity() * sizeof(std::uint32_t);
  for (int k = 0; k < kNumGridKinds; ++k) {
    bool shared = false;
    for (int j = 0; j < k; ++j) shared = shared || grids[j] == grids[k];
    if (grids[k] && !shared) b += grids[k]->stored.size() * sizeof(std::uint32_t);
  }
  return b;
}

void GoalHeuristics::stopBeyond(std::uint64_t path_cost) const {
  // One key per grid object (kinds may share one at different scales): the largest of its
  // kinds', so that each kind's cells below the path's cost stay exact.
  for (int k = 0; k < kNumGridKinds; ++k) {
    if (!grids[k] || !grids[k]->progress) continue;
    double units = 0.0;
    for (int j = 0; j < kNumGridKinds; ++j) {
      if (grids[j] == grids[k] && scale[j] > 0.0)
        units = std::max(units, static_cast<double>(path_cost) * kGridFraction / scale[j]);
    }
    const std::uint32_t key = units >= static_cast<double>(kUnreachable)
                                  ? kUnreachable
                                  : static_cast<std::uint32_t>(std::ceil(units));
    std::atomic<std::uint32_t>& stop = grids[k]->progress->stop_key;
    for (std::uint32_t cur = stop.load(std::memory_order_relaxed);
         key < cur && !stop.compare_exchange_weak(cur, key, std::memory_order_relaxed);) {
    }
  }
}

bool GoalHeuristics::anyAbandoned() const {
  return std::any_of(std::begin(grids), std::end(grids),
                     [](const auto& g) { return g && g->abandoned(); });
}

HeuristicGridBuilder::HeuristicGridBuilder(const LatticeGraph& graph)
    : HeuristicGridBuilder(graph, nullptr) {}

HeuristicGridBuilder::HeuristicGridBuilder(const HeuristicGridBuilder& previous,
                                           const LatticeGraph& graph)
    : HeuristicGridBuilder(graph, &previous) {}

HeuristicGridBuilder::HeuristicGridBuilder(const LatticeGraph& graph,
                                           const HeuristicGridBuilder* previous)
    : graph_(graph), width_(graph.width()), height_(graph.height()) {
  const LatticeConfig& c = graph.config();
  needed_[0] = c.heuristics.grid_anchor;
  needed_[1] = c.heuristics.num_inadmissible >= 1;
  needed_[2] = c.heuristics.num_inadmissible >= 2;
  needed_[3] = c.heuristics.num_inadmissible >= 3;
  // The anchor's grid: cells the centre may occupy (below inscribed), admissible scale.
  const int connectivity = c.heuristics.anchor_connectivity;
  if (needed_[0])
    buildKind(0, connectivity, graph.gridAnchorUnitsPerCell(), nullptr, kInscribedCost - 1,
              previous, &graph.gridAnchorMoveUnits());
  const double s = graph.cheapestUnitsPerCell();
  const bool kinematic = c.heuristics.inadmissible == LatticeConfig::Inadmissible::kKinematic;
  if (needed_[1] && needed_[0] && kinematic && graph.gridAnchorUnitsPerCell() > 0) {
    // The point robot's grid is the anchor's (where the centre may be), at full scale (the
    // classes of move the anchor raises above its smallest scale a little more).
    alias_[1] = 0;
    scale_[1] = s / graph.gridAnchorUnitsPerCell();
  } else if (needed_[1]) {
    buildKind(1, 8, s, nullptr, kLethalCost - 1, previous);
    // Without inscribed cells the point robot's grid is the anchor's (same cells, same moves)
    // at another scale: compute it once.
    if (needed_[0] && connectivity == 8 && kinds_[1].level == kinds_[0].level &&
        graph.gridAnchorUnitsPerCell() > 0) {
      alias_[1] = 0;
      scale_[1] = s / graph.gridAnchorUnitsPerCell();
    }
  }
  // The openings: the paper's 8-connected grids on every cell below lethal; with the kinematic
  // heuristics, grids like the anchor's (its moves, where the centre may be) at full scale.
  auto opening = [&](int k, int which) {
    if (kinematic && needed_[0]) {
      buildKind(k, connectivity, s, graph.openedFree(which), kInscribedCost - 1, previous);
      if (kinds_[k].level == kinds_[0].level) {
        alias_[k] = 0;
        scale_[k] = scale_[1];
      }
    } else {
      buildKind(k, 8, s, graph.openedFree(which), kLethalCost - 1, previous);
      if (needed_[1] && kinds_[k].level == kinds_[1].level) {
        alias_[k] = alias_[1];
        scale_[k] = scale_[1];
      }
    }
  };
  if (needed_[2]) opening(2, 0);
  if (needed_[3]) {
    if (needed_[2] && graph.openingsEqual()) {
      alias_[3] = alias_[2];
      scale_[3] = scale_[2];
    } else {
      opening(3, 1);
    }
  }
  if (c.heuristics.grid_anchor && c.heuristics.coarse_anchor) {
    coarse_.reset(previous != nullptr && previous->coarse_
                      ? new CoarseLattice(*previous->coarse_, graph, graph.recomputed())
                      : new CoarseLattice(graph, c.heuristics.coarse_block));
  }
  // Identical kinds share their data (and their result).
  for (int k = 0; k < kNumGridKinds; ++k) {
    if (alias_[k] != k) kinds_[k] = Kind();
  }
}

void HeuristicGridBuilder::buildKind(int k, int connectivity, double units_per_cell,
                                     const std::vector<std::uint8_t>* mask,
                                     std::uint8_t max_cost_class,
                                     const HeuristicGridBuilder* previous,
                                     const std::vector<double>* move_units) {
  Kind& kind = kinds_[k];
  const int pw = width_ + 4, ph = height_ + 4;
  const std::vector<std::uint8_t>& cost = graph_.map().cost;
  CellRect cells{0, 0, width_, height_};
  if (previous != nullptr) {
    // Kind k's previous levels: its own, or those of the kind it was an alias of (equal).
    kind.level = previous->kinds_[previous->alias_[k]].level;
    cells = graph_.recomputed();
  } else {
    kind.level.assign(static_cast<std::size_t>(pw) * ph, 255);
  }
  for (int y = cells.y0; y < cells.y1; ++y) {
    for (int x = cells.x0; x < cells.x1; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * width_ + x;
      const std::uint8_t c = cost[i];
      const bool passable = c <= max_cost_class && (mask == nullptr || (*mask)[i]);
      kind.level[paddedIndex(width_, x, y)] = passable ? std::min<std::uint8_t>(c, 252) : 255;
    }
  }
  const std::vector<GridMove> moves = gridMoves(connectivity);
  const double pen = graph_.config().cost.penalty;
  kind.move_offsets.clear();
  kind.required.clear();
  kind.required_count.clear();
  kind.either_side.clear();
  kind.step.assign(moves.size() * 256, 0);
  kind.max_step = 0;
  kind.min_step = std::numeric_limits<std::uint32_t>::max();
  kind.walk_per_cell = std::numeric_limits<double>::infinity();
  kind.reach = 0;
  for (std::size_t m = 0; m < moves.size(); ++m) {
    const GridMove& mv = moves[m];
    kind.reach = std::max({kind.reach, std::abs(mv.dx), std::abs(mv.dy)});
    kind.move_offsets.push_back(static_cast<std::int64_t>(mv.dy) * pw + mv.dx);
    int count = 0;
    for (const CellOffset& r : mv.required) {
      if ((r.dx == 0 && r.dy == 0) || (r.dx == mv.dx && r.dy == mv.dy)) continue;
      kind.required.push_back(static_cast<std::int64_t>(r.dy) * pw + r.dx);
      ++count;
    }
    while (count < kMaxRequired) {  // pad with the move's own end (always checked anyway)
      kind.required.push_back(kind.move_offsets.back());
      ++count;
    }
    kind.required_count.push_back(static_cast<int>(mv.required.size()) - 2);
    kind.either_side.push_back(mv.either_side ? 1 : 0);
    const double units = move_units != nullptr ? (*move_units)[m] : units_per_cell;
    for (int c = 0; c < 256; ++c) {
      const double step =
          units * mv.length * (1.0 + pen * std::min(c, 252) / 252.0) * kGridFraction;
      kind.step[m * 256 + c] = static_cast<std::uint32_t>(std::min(std::floor(step), 1e9));
      if (c <= 252) {
        kind.max_step = std::max(kind.max_step, kind.step[m * 256 + c]);
        kind.min_step = std::min(kind.min_step, kind.step[m * 256 + c]);
      }
    }
    // per_cell * length <= step - 1/1024 for every move's cheapest step: ceil(per_cell * length)
    // <= step with room for the rounding of the square roots (GridDirection's proof).
    kind.walk_per_cell =
        std::min(kind.walk_per_cell, (kind.step[m * 256] - 1.0 / 1024) / mv.length);
  }
  kind.walk_per_cell = std::isfinite(kind.walk_per_cell) ? std::max(0.0, kind.walk_per_cell) : 0.0;
}

namespace {

/// Makes sure the pages of a tracked grid's cells within `reach` of padded cell i have been
/// written (with zeros: kUnreachable) before the Dijkstra reads them. It reads a neighbour's
/// distance before writing it, and a fresh page read first is mapped to the kernel's zero page,
/// then copied on the first write with a TLB flush across the cores, the search's among them: on
/// a 2000 x 2000 map that made the search start 1.6 times later than with every page written in
/// order first (results/smac.md). Cells reached form a connected set, so the written ones are one
/// range of rows, grown a chunk at a time; the rows the grid never reaches stay untouched pages.
inline void coverWritten(GridProgress& p, std::uint32_t* dist, std::size_t i, std::size_t reach) {
  if (i >= p.written_lo + reach && i + reach < p.written_hi) return;
  constexpr std::size_t kChunk = std::size_t{1} << 14;  // cells: 64 KB, 16 pages
  constexpr std::size_t kPage = 1024;                   // cells per 4 KB page
  const std::size_t lo = (i > reach + kChunk ? i - reach - kChunk : 0) / kPage * kPage;
  const std::size_t hi = std::min(p.cells, (i + reach + kChunk + kPage) / kPage * kPage);
  if (p.written_lo == p.written_hi) {  // nothing yet
    std::memset(dist + lo, 0, (hi - lo) * sizeof(std::uint32_t));
    p.written_lo = lo;
    p.written_hi = hi;
    return;
  }
  if (lo < p.written_lo) {
    std::memset(dist + lo, 0, (p.written_lo - lo) * sizeof(std::uint32_t));
    p.written_lo = lo;
  }
  if (hi > p.written_hi) {
    std::memset(dist + p.written_hi, 0, (hi - p.written_hi) * sizeof(std::uint32_t));
    p.written_hi = hi;
  }
}

/// Whether popping `key` ends a tracked grid at its stop key (GoalHeuristics::stopBeyond): the
/// cells left are not needed; then it records so (stopped_at_key).
inline bool reachedStopKey(GridProgress& p, std::uint32_t key) {
  if (key < p.stop_key.load(std::memory_order_relaxed)) return false;
  p.stopped_at_key = true;
  return true;
}

/// Sets cell i's bit in GridProgress::final_bits (one writer: the thread computing the grid).
inline void markFinal(std::uint8_t* bits, std::size_t i) {
  std::uint8_t* b = bits + (i >> 3);
  const std::uint8_t v = __atomic_load_n(b, __ATOMIC_RELAXED);
  __atomic_store_n(b, static_cast<std::uint8_t>(v | (1u << (i & 7))), __ATOMIC_RELEASE);
}

inline bool isMarked(const std::uint8_t* bits, std::size_t i) {
  return (bits[i >> 3] >> (i & 7)) & 1u;
}

/// Whether popping (key, i) settles cell i, not a stale entry; tracked, it marks i final. The
/// first pop of a cell is its smallest key, hence (keys consistent) its final distance.
template <bool kTracked>
inline bool settles(std::uint8_t* bits, const std::uint32_t* dist, std::uint32_t key,
                    std::uint32_t i) {
  if constexpr (kTracked) {
    if (isMarked(bits, i)) return false;
    markFinal(bits, i);
    return true;
  } else {
    return key == decodeDistance(dist[i]);
  }
}

}  // namespace

GridDirection HeuristicGridBuilder::towardCell(const Kind& kind, std::int64_t px,
                                               std::int64_t py) const {
  GridDirection d;
  d.x = px;
  d.y = py;
  d.padded_width = width_ + 4;
  // The keys g + e stay below 32 bits if the distances do with room for the largest e.
  const std::uint64_t cells = static_cast<std::uint64_t>(width_ + 4) * (height_ + 4) +
                              static_cast<std::uint64_t>(width_ + height_ + 8);
  if (cells * kind.max_step >= kUnreachable - 1) return d;
  d.per_cell = kind.walk_per_cell;
  d.knights = kind.move_offsets.size() == 16;
  return d;
}

template <bool kTracked, class Queue>
bool HeuristicGridBuilder::dijkstra(const Kind& kind, std::uint32_t* dist, Queue& queue,
                                    const StopCondition* stop, GridProgress* progress,
                                    std::uint32_t* max_g) const {
  const std::size_t nm = kind.move_offsets.size();
  const std::int64_t* off = kind.move_offsets.data();
  std::uint8_t* bits = kTracked ? progress->final_bits.data() : nullptr;
  const std::size_t reach = writeReach(kind);
  // The largest distance settled, kept in a register (stores to dist could alias *max_g).
  std::uint32_t top_g = 0;
  auto done = [&](bool complete) {
    if (max_g != nullptr) *max_g = std::max(*max_g, top_g);
    return complete;
  };
  for (std::uint32_t pops = 0; !queue.empty();) {
    const auto [key, i] = queue.pop();
    if constexpr (kTracked) {
      if (reachedStopKey(*progress, key)) return done(true);
    }
    if (!settles<kTracked>(bits, dist, key, i)) continue;
    if constexpr (kTracked) coverWritten(*progress, dist, i, reach);
    const std::uint32_t d = decodeDistance(dist[i]);
    top_g = std::max(top_g, d);
    if ((++pops & 4095) == 0 && stop != nullptr && stop->requested()) return done(false);
    for (std::size_t m = 0; m < nm; ++m) {
      const std::uint32_t w = moveCost(kind, i, m);
      if (w == kUnreachable) continue;
      const std::size_t j = static_cast<std::size_t>(static_cast<std::int64_t>(i) + off[m]);
      // Saturating before the comparison, as dijkstraUnrolled does: a distance past kUnreachable -
      // 1 is still a reachable cell.
      const std::uint32_t v = static_cast<std::uint32_t>(
          std::min<std::uint64_t>(static_cast<std::uint64_t>(d) + w, kUnreachable - 1));
      if (v < decodeDistance(dist[j])) {
        storeDistance(dist, j, v);
        queue.push(kTracked ? v + progress->direction.atIndex(j) : v,
                   static_cast<std::uint32_t>(j));
      }
    }
  }
  return done(true);
}

// The 8- and 16-connected cases, unrolled: the eight neighbours are read once and serve as the
// side cells of the diagonal moves and the intermediate cells of the knight moves. Same result
// as the generic loop (moves in gridMoves() order: (-1,-1) (0,-1) (1,-1) (-1,0) (1,0) (-1,1)
// (0,1) (1,1), then the knight moves (2,1) (1,2) (-1,2) (-2,1) (-2,-1) (-1,-2) (1,-2) (2,-1),
// whose segments cross two cells between their ends, e.g. (1,0) and (1,1) for (2,1)).
constexpr std::size_t kPrefetchAhead = 4;

template <bool kKnights, bool kTracked, class Queue>
bool HeuristicGridBuilder::dijkstraUnrolled(const Kind& kind, std::uint32_t* dist, Queue& queue,
                                            const StopCondition* stop, GridProgress* progress,
                                            std::uint32_t* max_g) const {
  const std::uint8_t* __restrict level = kind.level.data();
  const std::int64_t pw = width_ + 4;
  const std::uint32_t* step = kind.step.data();
  const std::uint32_t* s_sw = step + 0 * 256;
  const std::uint32_t* s_s = step + 1 * 256;
  const std::uint32_t* s_se = step + 2 * 256;
  const std::uint32_t* s_w = step + 3 * 256;
  const std::uint32_t* s_e = step + 4 * 256;
  const std::uint32_t* s_nw = step + 5 * 256;
  const std::uint32_t* s_n = step + 6 * 256;
  const std::uint32_t* s_ne = step + 7 * 256;
  std::uint8_t* bits = kTracked ? progress->final_bits.data() : nullptr;
  const GridDirection toward = kTracked ? progress->direction : GridDirection();
  const std::size_t reach = writeReach(kind);
  const bool directed = kTracked && toward.per_cell > 0;  // else Dijkstra's order, no e
  // The largest distance settled, kept in a register (stores to dist could alias *max_g).
  std::uint32_t top_g = 0;
  auto done = [&](bool complete) {
    if (max_g != nullptr) *max_g = std::max(*max_g, top_g);
    return complete;
  };
  for (std::uint32_t pops = 0; !queue.empty();) {
    // Not a structured binding: clang before 16 cannot capture one in the lambda below.
    const std::pair<std::uint32_t, std::uint32_t> top = queue.pop();
    const std::uint32_t key = top.first, i = top.second;
    // Cells of one key lie scattered along the wavefront: load the distance and the level
    // rows of the cell popped a few pops from now (the stale check below was a fifth of the
    // time on large cost maps).
    {
      const std::uint32_t a = queue.upcoming(kPrefetchAhead, i);
      __builtin_prefetch(dist + a);
      __builtin_prefetch(dist + a - pw);
      __builtin_prefetch(dist + a + pw);
      __builtin_prefetch(level + a - pw);
      __builtin_prefetch(level + a + pw);
      if constexpr (kTracked) __builtin_prefetch(bits + (a >> 3));
    }
    if constexpr (kTracked) {
      if (reachedStopKey(*progress, key)) return done(true);
    }
    if (!settles<kTracked>(bits, dist, key, i)) continue;
    if constexpr (kTracked) coverWritten(*progress, dist, i, reach);
    const std::uint32_t d = decodeDistance(dist[i]);
    top_g = std::max(top_g, d);
    if ((++pops & 4095) == 0 && stop != nullptr && stop->requested()) return done(false);
    // The popped cell's padded coordinates, for the keys toward the search's start.
    const std::uint32_t upw = static_cast<std::uint32_t>(pw);  // a 32-bit division is faster
    const std::int64_t ix = directed ? i % upw : 0;
    const std::int64_t iy = directed ? i / upw : 0;
    const unsigned c0 = level[i];
    const unsigned lw = level[i - 1], le = level[i + 1], ls = level[i - pw], ln = level[i + pw];
    // Inlined by force (and the moves below): GCC kept some out of line.
    auto relax = [&](std::size_t j, unsigned c, const std::uint32_t* s, int dx, int dy)
        __attribute__((always_inline)) {
      // Saturating: min(distance, kUnreachable - 1) is still admissible and consistent.
      const std::uint32_t nd = static_cast<std::uint32_t>(
          std::min<std::uint64_t>(static_cast<std::uint64_t>(d) + s[c], kUnreachable - 1));
      if (nd < decodeDistance(dist[j])) {
        storeDistance(dist, j, nd);
        queue.push(directed ? nd + toward.at(ix + dx, iy + dy) : nd, static_cast<std::uint32_t>(j));
      }
    };
    if (lw != 255) relax(i - 1, std::max(c0, lw), s_w, -1, 0);
    if (le != 255) relax(i + 1, std::max(c0, le), s_e, 1, 0);
    if (ls != 255) relax(i - pw, std::max(c0, ls), s_s, 0, -1);
    if (ln != 255) relax(i + pw, std::max(c0, ln), s_n, 0, 1);
    // Diagonals (GridMove::either_side): one passable side cell suffices, the cheaper counts;
    // 255 (blocked) is above every cost class, so min() picks a passable side if there is one.
    auto diagonal = [&](int dx, int dy, unsigned side_a, unsigned side_b, const std::uint32_t* s)
        __attribute__((always_inline)) {
      const unsigned side = std::min(side_a, side_b);
      if (side == 255) return;
      const std::size_t j = static_cast<std::size_t>(static_cast<std::int64_t>(i) + dy * pw + dx);
      const unsigned l = level[j];
      if (l != 255) relax(j, std::max({c0, side, l}), s, dx, dy);
    };
    diagonal(-1, -1, ls, lw, s_sw);
    diagonal(1, -1, ls, le, s_se);
    diagonal(-1, 1, ln, lw, s_nw);
    diagonal(1, 1, ln, le, s_ne);
    if constexpr (kKnights) {
      // Both cells between the ends are required (255 stays above every class, as above).
      const unsigned lsw = level[i - pw - 1], lse = level[i - pw + 1], lnw = level[i + pw - 1],
                     lne = level[i + pw + 1];
      auto knight = [&](std::int64_t dx, std::int64_t dy, unsigned a, unsigned b, int m)
          __attribute__((always_inline)) {
        const unsigned mid = std::max(a, b);
        if (mid == 255) return;
        const std::size_t j = static_cast<std::size_t>(static_cast<std::int64_t>(i) + dy * pw + dx);
        const unsigned l = level[j];
        if (l != 255)
          relax(j, std::max({c0, mid, l}), step + m * 256, static_cast<int>(dx),
                static_cast<int>(dy));
      };
      knight(2, 1, le, lne, 8);
      knight(1, 2, ln, lne, 9);
      knight(-1, 2, ln, lnw, 10);
      knight(-2, 1, lw, lnw, 11);
      knight(-2, -1, lw, lsw, 12);
      knight(-1, -2, ls, lsw, 13);
      knight(1, -2, ls, lse, 14);
      knight(2, -1, le, lse, 15);
    }
  }
  return done(true);
}

template <bool kTracked, class Queue>
bool HeuristicGridBuilder::propagate(const Kind& kind, std::uint32_t* dist, Queue& queue,
                                     const StopCondition* stop, GridProgress* progress,
                                     std::uint32_t* max_g) const {
  switch (kind.move_offsets.size()) {
    case 8:
      return dijkstraUnrolled<false, kTracked>(kind, dist, queue, stop, progress, max_g);
    case 16:
      return dijkstraUnrolled<true, kTracked>(kind, dist, queue, stop, progress, max_g);
    default:
      return dijkstra<kTracked>(kind, dist, queue, stop, progress, max_g);
  }
}

bool HeuristicGridBuilder::dijkstraFromGoal(const Kind& kind, int gx, int gy, DistanceGrid& grid,
                                            const StopCondition* stop,
                                            GridProgress* progress) const {
  const int pw = width_ + 4;
  const std::size_t total = static_cast<std::size_t>(pw) * (height_ + 4);
  grid.width = width_;
  grid.height = height_;
  grid.max_distance = 0;
  // Every cell kUnreachable: fresh zero pages (encodeDistance). A grid computed in the
  // background is written as it goes (coverWritten), so that the rows it never reaches cost no
  // memory; one computed here is complete on return, and its pages are quicker written in order.
  grid.stored.reset(total);
  std::uint32_t* dist = grid.stored.data();
  const std::uint32_t goal = static_cast<std::uint32_t>(paddedIndex(width_, gx, gy));
  const bool passable = kind.level[goal] != 255;
  if (progress == nullptr) {
    if (!writeInSlices(dist, total, nullptr, stop)) return false;
  } else {
    // Written at once (read by the search before they are set: see coverWritten).
    progress->final_bits.assign(total / 8 + 1, 0);
    progress->cells = total;
    if (passable) coverWritten(*progress, dist, goal, writeReach(kind));
  }
  if (passable) storeDistance(dist, goal, 0);
  if (progress != nullptr) progress->filled.store(true, std::memory_order_release);
  if (!passable) return true;
  // Every finite distance is popped (max_g: the largest).
  auto search = [&](auto& queue) {
    std::uint32_t max_g = 0;
    bool complete = false;
    if (progress != nullptr) {
      queue.push(progress->direction.atIndex(goal), goal);
      complete = propagate<true>(kind, dist, queue, stop, progress, &max_g);
      if (!complete || progress->stopped_at_key)
        progress->frontier.store(queue.lastPopped(), std::memory_order_relaxed);
    } else {
      queue.push(0, goal);
      complete = propagate<false>(kind, dist, queue, stop, nullptr, &max_g);
    }
    grid.max_distance = max_g;
    return complete;
  };
  // Dial's queue needs every key within its span of the current one: a step (Dijkstra's order),
  // a step and the change of e along it, at most another step (GridDirection), so it is used
  // only when no distance can reach the saturation value.
  const std::uint32_t span =
      progress != nullptr && progress->direction.per_cell > 0 ? 2 * kind.max_step : kind.max_step;
  if (span < 8192 && !canSaturate(kind)) {
    detail::DialQueue q(span, progress != nullptr ? progress->direction.atIndex(goal) : 0);
    return search(q);
  }
  detail::RadixHeap q;
  return search(q);
}

bool HeuristicGridBuilder::run(const Kind& kind, int gx, int gy, DistanceGrid& grid,
                               const StopCondition* stop, GridProgress* progress) const {
  const bool complete = dijkstraFromGoal(kind, gx, gy, grid, stop, progress);
  if (progress != nullptr) {
    // Stopped at its key, it is done as far as anyone needs: not a stopped computation.
    if (complete && !progress->stopped_at_key) {
      progress->complete.store(true, std::memory_order_release);
    } else {
      progress->abandoned.store(true, std::memory_order_release);
    }
  }
  return complete;
}

bool HeuristicGridBuilder::writeInSlices(std::uint32_t* cells, std::size_t count,
                                         const std::uint32_t* source,
                                         const StopCondition* stop) const {
  constexpr std::size_t kSlice = std::size_t{1} << 20;
  for (std::size_t done = 0; done < count; done += kSlice) {
    if (stop != nullptr && stop->requested()) return false;
    const std::size_t n = std::min(kSlice, count - done);
    if (source != nullptr) {
      std::copy(source + done, source + done + n, cells + done);
    } else {
      std::memset(cells + done, 0, n * sizeof(std::uint32_t));
    }
  }
  return true;
}

bool HeuristicGridBuilder::canSaturate(const Kind& kind) const {
  const std::uint64_t total = static_cast<std::uint64_t>(width_ + 4) * (height_ + 4);
  return total * kind.max_step >= kUnreachable - 1;
}

std::uint32_t HeuristicGridBuilder::moveCost(const Kind& kind, std::size_t i, std::size_t m) const {
  const std::uint8_t* level = kind.level.data();
  const unsigned li = level[i];
  unsigned c = level[static_cast<std::size_t>(static_cast<std::int64_t>(i) + kind.move_offsets[m])];
  if (li == 255 || c == 255) return kUnreachable;
  c = std::max(c, li);
  const std::int64_t* r = kind.required.data() + m * kMaxRequired;
  const std::int64_t si = static_cast<std::int64_t>(i);
  if (kind.either_side[m]) {
    const unsigned side = std::min(level[si + r[0]], level[si + r[1]]);
    if (side == 255) return kUnreachable;
    c = std::max(c, side);
  } else {
    for (int k = 0; k < kind.required_count[m]; ++k) {
      const unsigned lr = level[si + r[k]];
      if (lr == 255) return kUnreachable;
      c = std::max(c, lr);
    }
  }
  return kind.step[m * 256 + c];
}

// Repairs a grid after a change (detail::repairDistances), exactly: the result is the grid
// run() computes on the new levels. The grids are distances from the goal, so a predecessor
// follows dijkstra()'s relaxation: the distance of j = i + move m is at most
// dist[i] + moveCost(i, m).
bool HeuristicGridBuilder::repairGrid(const Kind& kind, int gx, int gy, const DistanceGrid& old,
                                      const std::vector<CellRect>& changed, DistanceGrid& grid,
                                      const StopCondition* stop) const {
  const int pw = width_ + 4;
  const std::size_t total = static_cast<std::size_t>(pw) * (height_ + 4);
  // Saturated distances (kUnreachable - 1, old or new) break the equality test, and a step of 0
  // would let two cells hold each other up: such grids are computed in full (neither happens on
  // real maps: saturation takes a path of millions of cells).
  constexpr std::uint32_t kSaturated = kUnreachable - 1;
  if (old.stored.size() != total || kind.min_step == 0 || old.max_distance >= kSaturated) {
    return run(kind, gx, gy, grid, stop);
  }
  if (&grid != &old) {
    grid.width = width_;
    grid.height = height_;
    grid.stored.reset(total);
    if (!writeInSlices(grid.stored.data(), total, old.stored.data(), stop)) return false;
  }
  std::uint32_t* dist = grid.stored.data();
  const std::uint8_t* level = kind.level.data();
  const std::size_t nm = kind.move_offsets.size();
  const std::int64_t* off = kind.move_offsets.data();
  const std::uint32_t goal = static_cast<std::uint32_t>(paddedIndex(width_, gx, gy));
  // The cells whose moves (to or from them) may cost something else: a move's cells lie in the
  // box between its two ends.
  std::vector<CellRect> near;
  for (const CellRect& r : changed) {
    const CellRect d{std::max(0, r.x0 - kind.reach), std::max(0, r.y0 - kind.reach),
                     std::min(width_, r.x1 + kind.reach), std::min(height_, r.y1 + kind.reach)};
    if (d.x0 < d.x1 && d.y0 < d.y1) near.push_back(d);
  }
  auto forNear = [&](auto&& f) {
    for (const CellRect& r : near) {
      for (int y = r.y0; y < r.y1; ++y) {
        for (int x = r.x0; x < r.x1; ++x) f(static_cast<std::uint32_t>(paddedIndex(width_, x, y)));
      }
    }
  };
  auto holds = [&](std::uint32_t c) {
    if (level[c] == 255) return false;
    if (c == goal) return true;
    for (std::size_t m = 0; m < nm; ++m) {
      const std::uint32_t i = static_cast<std::uint32_t>(c - off[m]);
      const std::uint32_t di = decodeDistance(dist[i]);
      if (di == kUnreachable) continue;
      const std::uint32_t w = moveCost(kind, i, m);
      if (w != kUnreachable && static_cast<std::uint64_t>(di) + w == decodeDistance(dist[c]))
        return true;
    }
    return false;
  };
  auto along = [&](std::int64_t sign) {  // the 8 or 16 moves are symmetric: out of = into
    return [&, sign](std::uint32_t c, auto&& f) {
      for (std::size_t m = 0; m < nm; ++m) f(static_cast<std::uint32_t>(c + sign * off[m]));
    };
  };
  detail::RadixHeap queue;
  auto resume = [&](detail::RadixHeap& q) { return propagate<false>(kind, dist, q, stop); };
  if (!detail::repairDistances(detail::EncodedCells{dist}, goal, 1, level[goal] != 255, forNear,
                               holds, along(+1), along(-1), resume, stop, queue)) {
    return false;
  }
  // The cells it did not pop keep old distances; a bound is enough (a saturated distance would
  // have been popped last).
  grid.max_distance = std::max(old.max_distance, queue.lastPopped());
  if (grid.max_distance >= kSaturated) return run(kind, gx, gy, grid, stop);
  return true;
}

DistanceGrid HeuristicGridBuilder::computeOne(GridKind kind, int gx, int gy) const {
  const int k = alias_[static_cast<int>(kind)];
  DistanceGrid g;
  run(kinds_[k], gx, gy, g);
  return g;
}

std::shared_ptr<const GoalHeuristics> HeuristicGridBuilder::compute(
    int gx, int gy, int gh, bool inadmissible, unsigned threads, bool backward,
    const StopCondition* stop, const std::pair<int, int>* search_start) const {
  return computeOrRepair(gx, gy, gh, inadmissible, threads, backward, stop, nullptr, nullptr,
                         search_start);
}

std::shared_ptr<const GoalHeuristics> HeuristicGridBuilder::repair(
    std::shared_ptr<const GoalHeuristics> old, const std::vector<CellRect>& changed,
    bool inadmissible, unsigned threads, bool backward, const StopCondition* stop) const {
  const int gx = old->goal_x, gy = old->goal_y, gh = old->goal_heading;
  return computeOrRepair(gx, gy, gh, inadmissible, threads, backward, stop, std::move(old),
                         &changed, nullptr);
}

bool HeuristicGridBuilder::runTask(Job& job, int k, const StopCondition* stop,
                                   bool complete_here) const {
  if (k < 0) {
    const std::shared_ptr<const GoalHeuristics>& old = job.old;
    job.out->coarse = old && !old->coarse.empty()
                          ? coarse_->repairDistances(old->coarse, *job.changed, job.gx, job.gy,
                                                     job.gh, job.backward, stop)
                          : coarse_->distances(job.gx, job.gy, job.gh, job.backward, stop);
    job.out->coarse_lattice = coarse_.get();
    return !job.out->coarse.empty();
  }
  if (job.base[k] != nullptr)
    return repairGrid(kinds_[k], job.gx, job.gy, *job.base[k], *job.changed, *job.result[k], stop);
  // A grid complete before anyone reads it needs no progress (no bits to set).
  if (complete_here) job.result[k]->progress.reset();
  return run(kinds_[k], job.gx, job.gy, *job.result[k], stop, job.result[k]->progress.get());
}

void HeuristicGridBuilder::work(Job& job, const StopCondition* stop, bool complete_here) const {
  for (std::size_t t; !job.stopped.load(std::memory_order_relaxed) &&
                      (t = job.next.fetch_add(1)) < job.tasks.size();) {
    if (!runTask(job, job.tasks[t], stop, complete_here))
      job.stopped.store(true, std::memory_order_relaxed);
  }
}

std::shared_ptr<const GoalHeuristics> HeuristicGridBuilder::computeOrRepair(
    int gx, int gy, int gh, bool inadmissible, unsigned threads, bool backward,
    const StopCondition* stop, std::shared_ptr<const GoalHeuristics> old,
    const std::vector<CellRect>* changed, const std::pair<int, int>* search_start) const {
  const auto t0 = std::chrono::steady_clock::now();
  reapBackground(false);
  auto job = std::make_shared<Job>();
  job->gx = gx;
  job->gy = gy;
  job->gh = gh;
  job->backward = backward;
  job->changed = changed;
  auto heuristics = std::make_shared<GoalHeuristics>();
  GoalHeuristics& out = *heuristics;
  job->out = heuristics.get();
  out.goal_x = gx;
  out.goal_y = gy;
  out.goal_heading = gh;
  bool wanted[kNumGridKinds];
  for (int k = 0; k < kNumGridKinds; ++k) wanted[k] = needed_[k] && (k == 0 || inadmissible);
  std::vector<int>& tasks = job->tasks;
  if (coarse_) tasks.push_back(-1);  // the abstraction: usually the longest, so first
  for (int k = 0; k < kNumGridKinds; ++k) {
    if (wanted[k] && alias_[k] == k) tasks.push_back(k);
  }
  for (int k = 0; k < kNumGridKinds; ++k) {
    if (wanted[k] && !wanted[alias_[k]] &&
        std::find(tasks.begin(), tasks.end(), alias_[k]) == tasks.end())
      tasks.push_back(alias_[k]);
  }
  // old's grid of kind k can be repaired into kind k's if it holds kind k's own distances
  // (another kind's, rescaled, cannot), for the same map size (repair() passes old's goal), and
  // is complete (a grid whose background thread was stopped is not).
  const DistanceGrid** base = job->base;
  for (int k : tasks) {
    const DistanceGrid* g = k >= 0 && old ? old->grids[k].get() : nullptr;
    if (g != nullptr && g->progress && !g->progress->waitComplete()) g = nullptr;
    if (g != nullptr && old->scale[k] == 1.0 && g->width == width_ && g->height == height_)
      base[k] = g;
  }
  // A grid nobody else holds (the caller gave up old, and no other task reads it) is repaired in
  // place: copying a big grid costs more than the repair itself. The grids in GoalHeuristics
  // are const only to their readers; this builder made them.
  const bool owned = old && old.use_count() == 1;
  std::shared_ptr<DistanceGrid>* result = job->result;
  for (int k : tasks) {
    if (k < 0) continue;
    const bool alone = base[k] != nullptr && std::count(base, base + kNumGridKinds, base[k]) == 1;
    if (owned && alone) {
      for (int j = 0; j < kNumGridKinds; ++j) {
        if (old->grids[j].get() == base[k])
          result[k] = std::const_pointer_cast<DistanceGrid>(old->grids[j]);
      }
    } else {
      result[k] = std::make_shared<DistanceGrid>();
    }
  }
  job->old = std::move(old);
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  // Starting threads costs more than a small map's grids.
  if (static_cast<std::size_t>(width_) * height_ < 20000) threads = 1;
  const std::size_t grid_tasks = tasks.size() - (coarse_ ? 1 : 0);
  // The search may start early if other threads can complete the grids meanwhile.
  const bool early = search_start != nullptr && !job->old && threads >= 2 && grid_tasks > 0;
  if (early) {
    // The background threads take the grids; this thread the abstraction, then helps.
    const std::size_t helpers = std::min<std::size_t>(threads - 1, grid_tasks);
    // The A* order pays when the search can start as soon as the start is final. With more
    // grids than helpers this thread completes the rest first, time in which the helpers'
    // Dijkstras, quicker to complete, get further than A*s (a rectangular robot's first paths
    // came 10-15 % later with A*s, measured in results/smac.md).
    const bool toward_start = grid_tasks <= helpers;
    const std::int64_t sx = search_start->first + 2, sy = search_start->second + 2;
    for (int k : tasks) {
      if (k < 0) continue;
      result[k]->progress = std::make_shared<GridProgress>();
      GridDirection& d = result[k]->progress->direction;
      d = towardCell(kinds_[k], sx, sy);
      if (!toward_start) d.per_cell = 0.0;
    }
    if (coarse_) job->next.store(1);
    {
      std::lock_guard<std::mutex> lock(background_mutex_);
      for (std::size_t t = 0; t < helpers; ++t) {
        background_.emplace_back();
        Background& b = background_.back();
        b.job = job;
        b.thread = std::thread([this, job, &b] {
          work(*job, &job->background_stop);
          b.done.store(true, std::memory_order_release);
        });
      }
    }
    if (coarse_ && !runTask(*job, -1, stop)) job->stopped.store(true);
    // More grids than helpers: this thread takes some too (those it takes it completes, in
    // Dijkstra's order, before returning them).
    if (grid_tasks > helpers) work(*job, stop, true);
    // Until the search's first cell is final in every grid, or a task or the caller stopped
    // (a helper's stopped task sets job->stopped too). The caller's stop is read before ready():
    // the helpers do not see it, and a small abstraction may finish before its first check, so
    // a call stopped before it returns must not return grids.
    const std::size_t first = paddedIndex(width_, search_start->first, search_start->second);
    auto ready = [&] {
      return std::all_of(tasks.begin(), tasks.end(), [&](int k) {
        if (k < 0 || !result[k]->progress) return true;  // none: completed by this thread
        const GridProgress& p = *result[k]->progress;
        return p.filled.load(std::memory_order_acquire) &&
               (p.isFinal(first) || p.complete.load(std::memory_order_acquire));
      });
    };
    for (unsigned spins = 0;; pause(spins)) {
      if (stop != nullptr && stop->requested()) job->stopped.store(true);
      if (job->stopped.load() || ready()) break;
    }
    if (job->stopped.load()) {
      job->cancel.store(true);
      return nullptr;
    }
  } else {
    const std::size_t n = std::min<std::size_t>(threads, tasks.size());
    std::vector<std::thread> pool;
    for (std::size_t t = 1; t < n; ++t) pool.emplace_back([&] { work(*job, stop); });
    work(*job, stop);
    for (auto& th : pool) th.join();
    if (job->stopped.load()) return nullptr;
  }
  for (int k = 0; k < kNumGridKinds; ++k) {
    if (wanted[k]) {
      out.grids[k] = result[alias_[k]];
      out.scale[k] = scale_[k];
    }
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return heuristics;
}

}  // namespace lattice
}  // namespace amha
