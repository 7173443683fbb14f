// 2-D distance grids from the goal, the heuristics of the lattice search:
//  - the anchor's grid: an 8-connected, cost-aware Dijkstra over the cells the robot's centre
//    may occupy, with step costs scaled so that it is a relaxation of the lattice (admissible
//    and consistent, see LatticeGraph::gridAnchorUnitsPerCell);
//  - the inadmissible ones (the paper's): an 8-connected Dijkstra for a point robot, and the
//    same on free space opened by the inscribed and by the circumscribed radius.
// Costs are integers, so a bucket queue or a radix heap (monotone integer queues) replaces the
// binary heap; the grids are independent and computed in parallel threads. Given the cell where
// the search begins, compute() returns once that cell's distance is final and leaves the rest of
// each grid to a background thread (GridProgress), which computes it as an A* toward that cell
// (GridDirection): the search starts after a fraction of the map, while the grid is completed.
// A planner that will not reuse the grids lets that thread stop once the search has a path and
// the keys pass its cost (GoalHeuristics::stopBeyond): the cells beyond are never needed.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include "amha_planner/lattice/detail/coarse_lattice.h"
#include "amha_planner/lattice/detail/footprint.h"
#include "amha_planner/lattice/detail/grid_moves.h"
#include "amha_planner/lattice/detail/zeroed_array.h"
#include "amha_planner/search/stop_condition.h"
#include "amha_planner/search/types.h"

namespace amha {
namespace lattice {

class LatticeGraph;

/// Unreachable cells of a grid hold this.
constexpr std::uint32_t kUnreachable = 0xFFFFFFFFu;
/// Grid values are in 1/kGridFraction cost units (each step is rounded down, so the finer unit
/// keeps the rounding loss small); heuristic value = grid value / kGridFraction.
constexpr std::uint32_t kGridFraction = 4;

/// The order in which a grid handed out early is computed: an A* from the goal toward the
/// search's first cell, key g + e(cell), so that the first cell is final after far fewer cells
/// than a Dijkstra's disc (Smac's obstacle heuristic does the same). e is the length of the
/// shortest obstacle-free walk of the grid's moves (8- or 16-connected) to that cell, in padded
/// coordinates, times `per_cell`, rounded down: a metric of the move graph, so
/// |walk(a) - walk(b)| <= length for a move between a and b, and no square root to take. With
/// per_cell * length <= the cheapest step of every move (HeuristicGridBuilder::buildKind),
///   e(a) <= floor(per_cell * walk(b) + per_cell * length) <= e(b) + ceil(per_cell * length)
///        <= e(b) + step
/// for every move between a and b, either way: e is consistent, the keys never decrease, and a
/// cell's distance is final when it is popped. per_cell = 0 is Dijkstra's order.
struct GridDirection {
  std::int64_t x = 0, y = 0;  ///< the padded cell toward which the grid is computed
  std::int64_t padded_width = 0;
  double per_cell = 0.0;
  bool knights = false;  ///< 16-connected moves (else 8)
  std::uint32_t at(std::int64_t px, std::int64_t py) const {
    const std::int64_t ax = px > x ? px - x : x - px, ay = py > y ? py - y : y - py;
    const double hi = static_cast<double>(ax > ay ? ax : ay);
    const double lo = static_cast<double>(ax > ay ? ay : ax);
    constexpr double kSqrt2 = 1.4142135623730951, kSqrt5 = 2.23606797749979;
    // Along the two moves either side of the direction: (1,0) and (1,1); with knights (1,0) and
    // (2,1) up to a slope of 1/2, then (2,1) and (1,1).
    const double walk = !knights       ? lo * kSqrt2 + (hi - lo)
                        : 2 * lo <= hi ? lo * kSqrt5 + (hi - 2 * lo)
                                       : (hi - lo) * kSqrt5 + (2 * lo - hi) * kSqrt2;
    return static_cast<std::uint32_t>(per_cell * walk);
  }
  std::uint32_t atIndex(std::size_t i) const {
    const std::int64_t w = padded_width;
    return at(static_cast<std::int64_t>(i) % w, static_cast<std::int64_t>(i) / w);
  }
};

/// A grid's cells store their distances inverted (~distance): kUnreachable is 0, so a grid begins
/// as fresh zero pages (ZeroedArray) and a page costs memory only once the Dijkstra reaches it. A
/// grid stopped early (GoalHeuristics::stopBeyond) then holds only the pages its search needed.
inline std::uint32_t encodeDistance(std::uint32_t d) { return ~d; }
inline std::uint32_t decodeDistance(std::uint32_t stored) { return ~stored; }

/// Which cells of a grid that a background thread still completes are final: one bit per padded
/// cell, set (release) when the cell is popped; its distance, stored before, never changes after.
/// A reader loads the bit (acquire), then the cell.
struct GridProgress {
  std::atomic<bool> filled{false};    ///< the cells and bits exist (release: readers may look)
  std::atomic<bool> complete{false};  ///< every cell is final (unreachable ones never get a bit)
  /// Stopped before completion (the builder was destroyed first, or the keys reached stop_key):
  /// read() returns a lower bound for the cells that are not final.
  std::atomic<bool> abandoned{false};
  /// The thread computing the grid stops (abandons it) once a key popped reaches this: cells
  /// beyond it are not needed (GoalHeuristics::stopBeyond). kUnreachable: never.
  std::atomic<std::uint32_t> stop_key{kUnreachable};
  /// Whether the keys reached stop_key (written by the computing thread before `abandoned`).
  bool stopped_at_key = false;
  /// The computing thread's own: the padded cells [written_lo, written_hi) whose pages it has
  /// written ahead of the Dijkstra (heuristic_grids.cpp, coverWritten), and the grid's size.
  std::size_t written_lo = 0, written_hi = 0, cells = 0;
  /// The last key popped, stored before `abandoned`: a cell not popped then has g + e >= it.
  std::atomic<std::uint32_t> frontier{0};
  std::vector<std::uint8_t> final_bits;  ///< written before `filled`, then bit by bit
  GridDirection direction;               ///< set before `filled`

  /// Whether cell i's distance is final; needs `filled`.
  bool isFinal(std::size_t i) const {
    return (__atomic_load_n(final_bits.data() + (i >> 3), __ATOMIC_ACQUIRE) >> (i & 7)) & 1u;
  }
  /// Cell i's final distance, waiting for it (the background thread makes progress on its own).
  /// Abandoned, a cell that is not final reads as max(0, frontier - e(cell)): every such cell
  /// has distance >= that, and, e being consistent both ways, frontier - e is consistent, so the
  /// grid stays a consistent lower bound (min(distance, frontier - e), then max with 0).
  /// `stored`: the grid's cells (encoded, DistanceGrid::stored).
  std::uint32_t read(const std::uint32_t* stored, std::size_t i) const;
  /// An abandoned grid's value for a cell that is not final, whose e is `e`.
  std::uint32_t boundBeyond(std::uint32_t e) const {
    const std::uint32_t f = frontier.load(std::memory_order_relaxed);
    return f > e ? f - e : 0;
  }
  /// Waits until the grid is complete; false if it was abandoned.
  bool waitComplete() const;
};

/// Index of cell (x, y) of a grid `width` cells wide, stored with a 2-cell border (padded width
/// width + 4): the one layout of the grids, their cost classes and the search's first cell.
inline std::size_t paddedIndex(int width, int x, int y) {
  return static_cast<std::size_t>(y + 2) * (width + 4) + (x + 2);
}

/// One Dijkstra grid, stored with a 2-cell blocked border (padded width width + 4).
struct DistanceGrid {
  int width = 0, height = 0;
  /// The padded cells' distances, encoded (encodeDistance); read them with at().
  ZeroedArray<std::uint32_t> stored;
  /// No finite distance exceeds this (the largest one after a full computation; kUnreachable - 1
  /// if a distance saturated).
  std::uint32_t max_distance = 0;
  /// Set when a background thread completes the grid (then read cells through at() only); null
  /// for a grid complete when it was handed out.
  std::shared_ptr<GridProgress> progress;
  std::uint32_t at(int x, int y) const {
    const std::size_t i = paddedIndex(width, x, y);
    if (!progress) return decodeDistance(stored[i]);
    // Inline while the cell is final (GridProgress); out of line only to wait.
    if (progress->isFinal(i))
      return decodeDistance(__atomic_load_n(stored.data() + i, __ATOMIC_RELAXED));
    // Stopped (GridProgress::read's bound), inline: a stopped grid is read so for the whole
    // proof, and the search knows (x, y), which atIndex() would divide out of i.
    if (progress->abandoned.load(std::memory_order_acquire))
      return progress->boundBeyond(progress->direction.at(x + 2, y + 2));
    return progress->read(stored.data(), i);
  }
  /// Whether every cell is final (then read them with atComplete()): no progress, or its
  /// Dijkstra has ended (an acquire, so that the plain reads after it see the distances).
  bool complete() const { return !progress || progress->complete.load(std::memory_order_acquire); }
  /// A cell of a grid that complete() said is complete, without at()'s check.
  std::uint32_t atComplete(int x, int y) const {
    return decodeDistance(stored[paddedIndex(width, x, y)]);
  }
  /// Whether it was stopped before completion (GridProgress::abandoned): cells not final read as
  /// a lower bound measured toward the search it was computed for, so it is not reused.
  bool abandoned() const { return progress && progress->abandoned.load(std::memory_order_acquire); }
  /// Every padded cell's distance as stored (decoded), for comparisons in tests.
  std::vector<std::uint32_t> distances() const;
};

/// Which grid; the anchor grid exists only with LatticeConfig::Heuristics::grid_anchor.
enum class GridKind {
  kAnchor = 0,
  kPointRobot = 1,
  kInscribedOpening = 2,
  kCircumscribedOpening = 3
};
constexpr int kNumGridKinds = 4;

/// The grids for one goal.
struct GoalHeuristics {
  int goal_x = 0, goal_y = 0, goal_heading = 0;
  std::shared_ptr<const DistanceGrid> grids[kNumGridKinds];  ///< null if not needed
  /// Multiplier of each grid's values (1 unless the grid is another kind's, rescaled).
  double scale[kNumGridKinds] = {1.0, 1.0, 1.0, 1.0};
  /// Cost-to-go on the block abstraction (indexed by coarse_lattice->index), or empty.
  std::vector<std::uint32_t> coarse;
  const CoarseLattice* coarse_lattice = nullptr;
  double seconds = 0.0;  ///< wall time to compute them
  std::size_t bytes() const;
  /// Lets the threads still completing these grids stop once their keys (distance + e, in grid
  /// units) reach `path_cost` in cost units (for a grid scaled by s, path_cost / s): the search
  /// has a path of that cost, and a cell not final then reads as frontier - e (GridProgress::
  /// read), for which a state there has g + h >= path_cost whenever its g is at least e's
  /// length (e is a walk of the grid's cheapest steps to the search's first cell): the proof,
  /// which expands the states of f < its best path's cost, needs none of them. The result is
  /// consistent and admissible either way (read()); only reuse for another start suffers (the
  /// grids are then abandoned(): the planner's cache computes them again). Lowering only.
  void stopBeyond(std::uint64_t path_cost) const;
  /// Whether a grid was stopped before completion (DistanceGrid::abandoned).
  bool anyAbandoned() const;
};

/// Per-map data the grids need (levels with blocked cells, step-cost tables), built once.
class HeuristicGridBuilder {
 public:
  explicit HeuristicGridBuilder(const LatticeGraph& graph);
  /// The builder of `graph`, a graph built from previous's graph (LatticeGraph's incremental
  /// constructor): previous's tables, recomputed on graph.recomputed() only.
  HeuristicGridBuilder(const HeuristicGridBuilder& previous, const LatticeGraph& graph);
  /// Computes the anchor's tables and, if `inadmissible`, the inadmissible grids the
  /// configuration asks for, in parallel (up to `threads`, 0 = all hardware threads).
  /// `backward`: the tables are for a backward search, i.e. distances from (x, y, heading).
  /// Returns null if `stop` asked to stop before the tables were complete.
  /// `search_start` (a cell, or null): where the search begins. With it and two threads or more,
  /// the grids that other threads compute are returned as soon as that cell's distance is final
  /// in each, and those threads complete them in the background (DistanceGrid::progress);
  /// `stop` counts until the return only. Without it, every grid is complete on return.
  std::shared_ptr<const GoalHeuristics> compute(
      int goal_x, int goal_y, int goal_heading, bool inadmissible = true, unsigned threads = 0,
      bool backward = false, const StopCondition* stop = nullptr,
      const std::pair<int, int>* search_start = nullptr) const;
  /// The grids of old's goal (old->goal_x, goal_y, goal_heading) for this builder's map,
  /// repaired from `old`: grids computed for a version of this map whose cells differed from
  /// this one's only inside the rectangles `changed` (with the same configuration). Equal to
  /// compute() with the same arguments, but a grid visits only the cells whose distance the
  /// change can alter: the cells near the change and those whose shortest path led through it
  /// (the coarse distances likewise, CoarseLattice::repairDistances). A grid that cannot be
  /// repaired (old holds it at another kind's scale, or its distances could saturate) is
  /// computed in full. If `old` is the only reference to its grids (the caller moved its own
  /// in), they are repaired in place instead of copied, and are spent even if `stop` ends the
  /// repair. Null if `stop` asked to stop first.
  std::shared_ptr<const GoalHeuristics> repair(std::shared_ptr<const GoalHeuristics> old,
                                               const std::vector<CellRect>& changed,
                                               bool inadmissible = true, unsigned threads = 0,
                                               bool backward = false,
                                               const StopCondition* stop = nullptr) const;
  /// One grid alone (for tests and timing).
  DistanceGrid computeOne(GridKind kind, int goal_x, int goal_y) const;
  bool needed(GridKind kind) const { return needed_[static_cast<int>(kind)]; }
  /// Stops the grids still completing in the background (their readers then see them
  /// abandoned) and joins their threads.
  ~HeuristicGridBuilder();
  HeuristicGridBuilder(const HeuristicGridBuilder&) = delete;
  HeuristicGridBuilder& operator=(const HeuristicGridBuilder&) = delete;

 private:
  struct Job;
  /// A thread completing grids after compute() returned, and its job. The thread holds the job;
  /// this only reaches it to cancel, so a finished job's grids go with the last GoalHeuristics
  /// holding them, not at the next compute().
  struct Background {
    std::thread thread;
    std::weak_ptr<Job> job;
    std::atomic<bool> done{false};
  };
  struct Kind {
    std::vector<std::uint8_t> level;  // padded; 255 = blocked, else the cost class 0..252
    std::vector<std::int64_t> move_offsets;
    std::vector<std::int64_t> required;  // per move: kMaxRequired offsets (the two ends excluded)
    std::vector<int> required_count;
    std::vector<char> either_side;    // per move: GridMove::either_side
    std::vector<std::uint32_t> step;  // per move, 256 cost classes
    std::uint32_t max_step = 0;
    std::uint32_t min_step = 0;  // of a passable move
    double walk_per_cell = 0.0;  // GridDirection::per_cell: the cheapest step per unit length
    int reach = 1;               // cells: the farthest a move's end or required cell lies
  };
  static constexpr int kMaxRequired = 4;
  HeuristicGridBuilder(const LatticeGraph& graph, const HeuristicGridBuilder* previous);
  /// Builds kind k's tables; its levels from the map, or from `previous` (whose levels for kind
  /// k are the previous map's) where graph_.recomputed() says nothing changed.
  /// `move_units`: the anchor's scale per move (null: units_per_cell for every move).
  void buildKind(int k, int connectivity, double units_per_cell,
                 const std::vector<std::uint8_t>* mask, std::uint8_t max_cost_class,
                 const HeuristicGridBuilder* previous,
                 const std::vector<double>* move_units = nullptr);
  /// compute() and repair(): repairs from `old` where it can (old and changed non-null).
  std::shared_ptr<const GoalHeuristics> computeOrRepair(
      int goal_x, int goal_y, int goal_heading, bool inadmissible, unsigned threads, bool backward,
      const StopCondition* stop, std::shared_ptr<const GoalHeuristics> old,
      const std::vector<CellRect>* changed, const std::pair<int, int>* search_start) const;
  /// Task k of a job (-1: the block abstraction; else grid kind k); false if stopped.
  /// `complete_here`: the calling thread returns the grid only once complete (it drops the
  /// grid's progress and computes it in Dijkstra's order).
  bool runTask(Job& job, int k, const StopCondition* stop, bool complete_here = false) const;
  /// Runs the job's tasks from its queue until none is left.
  void work(Job& job, const StopCondition* stop, bool complete_here = false) const;
  /// Joins the background threads that have finished (all of them, and stopping them first,
  /// if `all`).
  void reapBackground(bool all) const;
  // These return false when `stop` asked to stop (the grid is then incomplete).
  /// With `progress`, run() publishes how far the grid is final (GridProgress), filled first,
  /// and at the end that it is complete or abandoned.
  bool run(const Kind& kind, int goal_x, int goal_y, DistanceGrid& grid,
           const StopCondition* stop = nullptr, GridProgress* progress = nullptr) const;
  /// run()'s fill and Dijkstra.
  bool dijkstraFromGoal(const Kind& kind, int goal_x, int goal_y, DistanceGrid& grid,
                        const StopCondition* stop, GridProgress* progress) const;
  bool repairGrid(const Kind& kind, int goal_x, int goal_y, const DistanceGrid& old,
                  const std::vector<CellRect>& changed, DistanceGrid& grid,
                  const StopCondition* stop) const;  // grid may be old
  /// Writes `count` cells from `source`, or zeros (kUnreachable, encoded) if it is null, in
  /// slices that check `stop`: first touching a big grid's pages takes tens of milliseconds, and
  /// a grid computed in full is quicker with its pages written in order first.
  bool writeInSlices(std::uint32_t* cells, std::size_t count, const std::uint32_t* source,
                     const StopCondition* stop) const;
  /// How far (padded cells) from a cell popped its moves read and write: kind.reach rows and
  /// columns.
  std::size_t writeReach(const Kind& kind) const {
    return static_cast<std::size_t>(kind.reach) * (width_ + 5);
  }
  /// Whether a distance on this map could reach the saturation value kUnreachable - 1.
  bool canSaturate(const Kind& kind) const;
  /// The cost of move m from padded cell i (dijkstra()'s relaxation), kUnreachable if blocked.
  std::uint32_t moveCost(const Kind& kind, std::size_t i, std::size_t m) const;
  /// The order toward padded cell (px, py) for kind's grid (GridDirection): per_cell from the
  /// cheapest steps, or 0 (Dijkstra's order) if a key g + e could exceed 32 bits.
  GridDirection towardCell(const Kind& kind, std::int64_t px, std::int64_t py) const;
  // Dijkstra from the cells already in `queue` (with their distances in dist); stores distances
  // atomically; *max_g (if given) receives the largest distance popped. With `progress`
  // (kTracked): the queue's keys are g + e (progress->direction), a popped cell's bit is set.
  template <bool kTracked, class Queue>
  bool dijkstra(const Kind& kind, std::uint32_t* dist, Queue& queue, const StopCondition* stop,
                GridProgress* progress = nullptr, std::uint32_t* max_g = nullptr) const;
  /// The 8-connected (kKnights false) and 16-connected moves, unrolled.
  template <bool kKnights, bool kTracked, class Queue>
  bool dijkstraUnrolled(const Kind& kind, std::uint32_t* dist, Queue& queue,
                        const StopCondition* stop, GridProgress* progress = nullptr,
                        std::uint32_t* max_g = nullptr) const;
  /// dijkstra() with kind's moves: unrolled for 8 and 16, else the generic loop.
  template <bool kTracked, class Queue>
  bool propagate(const Kind& kind, std::uint32_t* dist, Queue& queue, const StopCondition* stop,
                 GridProgress* progress = nullptr, std::uint32_t* max_g = nullptr) const;

  const LatticeGraph& graph_;
  std::unique_ptr<CoarseLattice> coarse_;
  int width_ = 0, height_ = 0;
  Kind kinds_[kNumGridKinds];
  bool needed_[kNumGridKinds] = {false, false, false, false};
  int alias_[kNumGridKinds] = {0, 1, 2, 3};  // a kind computed as another (identical) kind
  double scale_[kNumGridKinds] = {1.0, 1.0, 1.0, 1.0};  // ... times this factor
  mutable std::mutex background_mutex_;
  mutable std::list<Background> background_;  // guarded by background_mutex_
};

}  // namespace lattice
}  // namespace amha
