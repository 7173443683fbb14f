// The displacement grid: a heading-blind cost-to-go for the anchor whose moves are the
// primitives themselves.
//
// A 2-D Dijkstra over the map's cells whose moves are the displacements (dx, dy) of the
// lattice's actions, of every heading. A move costs the cheapest action with its displacement
// (with the cost model's penalty for the worse of its two end cells) and needs the cells that
// the centre of every such action crosses to be below inscribed. Every lattice edge is thus one
// of its moves, allowed wherever the edge is valid and no dearer, so a cell's distance is the
// cost-to-go of a relaxation of the lattice (the heading dropped): admissible, and consistent on
// every edge (h(p) <= d(p, q) + h(q) for the edge's move). Unlike the anchor's 16-connected grid
// it needs no scale below 1: that grid must be scaled (LatticeGraph::computeAnchorScales)
// because an arc can be cheaper than every walk of the grid's moves, which shortens every
// distance by 1-2 %; here each arc is a move. Over the states the proof expands the grid is a
// median 0.1-1.1 % below the best heading's exact cost-to-go where the 16-connected one is
// 1.3-2.2 % below, and A* on the anchor with it, complete, expands 1.1-16 times fewer states
// on the Smac benchmark's queries (docs/results/smac.md, "The displacement grid").
//
// It costs 4-6 times that grid (48-52 moves up to 18 cells long, against 16 of one or two), so
// the search does not wait for it: LatticePlanner computes it on a helper thread beside the
// search (from its first path, for the anytime searches), and the search takes it up when it
// is complete (SearchProblem::upgradeHeuristics). The per-map part (moves, levels, clearance)
// is built with the planner, and only when LatticeConfig::Heuristics::displacement_grid asks.
#pragma once

#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "amha_planner/lattice/detail/zeroed_array.h"
#include "amha_planner/search/stop_condition.h"

namespace amha {
namespace lattice {

class LatticeGraph;
struct DisplacementField;

/// The A*'s guide toward the search's start (DisplacementGrid::compute), for a cell (dx, dy)
/// from it: floor(kappa |(dx, dy)|). One function, so that the A*'s keys and
/// DisplacementField::at agree to the unit.
inline std::uint64_t displacementGuide(double kappa, double dx, double dy) {
  return static_cast<std::uint64_t>(kappa * std::sqrt(dx * dx + dy * dy));
}

class DisplacementGrid {
 public:
  /// Unreachable cells hold this.
  static constexpr std::uint32_t kUnreachable = 0xFFFFFFFFu;

  /// The moves from the graph's actions, and the map's levels and clearance.
  explicit DisplacementGrid(const LatticeGraph& graph);

  /// Computes into out->dist the distances, in the lattice's cost units and padded cells: to
  /// (x, y) from every cell (to_cell, a forward search's heuristic) or from (x, y) (a backward
  /// search's). In the order of an A* toward (toward_x, toward_y), the search's first cell: key
  /// g + e, e(c) = floor(kappa |c - toward|) with kappa below every move's cost per cell (so
  /// |e(a) - e(b)| < a move's cost: e is consistent, and a cell's distance is final when popped).
  /// It stops once the smallest key reaches *bound (an upper bound on the search's optimal cost,
  /// which the search lowers as it finds paths; UINT64_MAX: none yet), or when every reachable
  /// cell is settled, and fills in out->stop_key, toward and kappa (DisplacementField::at).
  /// False, with `out` unusable, if `abandon` became true or `stop` asked to stop first.
  bool compute(int x, int y, bool to_cell, int toward_x, int toward_y,
               const std::atomic<std::uint64_t>* bound, DisplacementField* out,
               const std::atomic<bool>* abandon = nullptr,
               const StopCondition* stop = nullptr) const;

  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y + pad_) * static_cast<std::size_t>(padded_width_) +
           static_cast<std::size_t>(x + pad_);
  }
  /// Padded cells: a result of compute() takes 4 bytes each.
  std::size_t cellCount() const { return level_.size(); }
  std::size_t moveCount() const { return offsets_.size(); }

 private:
  /// A displacement, its cheapest base cost, the cells every action with it crosses (relative to
  /// its start cell, both ends included), and the farthest of them (Chebyshev).
  struct Move {
    int dx = 0, dy = 0;
    std::int64_t base_cost = 0;
    std::vector<std::pair<int, int>> cells;
    int reach = 0;
  };

  template <bool kToCell, class Queue>
  bool run(std::uint32_t* dist, Queue& queue, std::int64_t tx, std::int64_t ty,
           const std::atomic<std::uint64_t>* bound, std::uint64_t* stop_key,
           const std::atomic<bool>* abandon, const StopCondition* stop) const;

  int width_ = 0, height_ = 0, pad_ = 0, padded_width_ = 0;
  double kappa_ = 0.0;  // the guide's cost per cell (compute())
  std::vector<Move> moves_;
  std::vector<std::int64_t> offsets_;        // per move: dy * padded width + dx
  std::vector<std::uint8_t> reach_;          // per move: farthest needed cell (Chebyshev)
  std::vector<std::uint32_t> needed_begin_;  // per move: into needed_ (moves + 1 entries)
  std::vector<std::int64_t> needed_;         // cells other than the two ends, as offsets
  std::vector<std::uint32_t> step_;          // per move, per end level 0..255: its cost
  std::uint32_t max_step_ = 0;
  ZeroedArray<std::uint8_t> level_;  // padded: 0 = the centre may not be there, else 1 + cost
  ZeroedArray<std::uint8_t> clear_;  // padded: Chebyshev distance to a 0 cell, at most 255
};

/// A displacement grid's result, computed by one thread (DisplacementGrid::compute) while a
/// search polls `ready` (LatticeProblem::upgradeHeuristics); `abandon` asks that thread to give
/// up, and `bound` is the search's best path cost so far, where it may stop.
struct DisplacementField {
  ZeroedArray<std::uint32_t> dist;  ///< 1 + distance, 0 where not reached
  std::atomic<bool> ready{false};   ///< set (release) once the fields below are final
  std::atomic<bool> abandon{false};
  std::atomic<std::uint64_t> bound{UINT64_MAX};
  const std::uint32_t* origin = nullptr;  ///< map cell (0, 0) in dist
  std::int64_t stride = 0;                ///< cells between two rows
  std::uint64_t stop_key = UINT64_MAX;    ///< the key it stopped at; UINT64_MAX: complete
  int toward_x = 0, toward_y = 0;
  double kappa = 0.0;

  /// The heuristic: min(distance, stop_key - e(x, y)), at least 0 (kUnreachable only where a
  /// complete field reached nothing). A cell the A* settled has its distance there, below
  /// stop_key - e; any other has a distance of at least stop_key - e (the A*'s keys are
  /// monotone). So this is min(true distance, stop_key - e): a minimum of two consistent,
  /// admissible functions (e is consistent), and so consistent and admissible.
  std::uint32_t at(int x, int y) const {
    const std::uint32_t v = origin[static_cast<std::int64_t>(y) * stride + x] - 1u;
    if (stop_key == UINT64_MAX) return v;
    const std::uint64_t e = displacementGuide(kappa, x - toward_x, y - toward_y);
    const std::uint64_t lb = stop_key > e ? stop_key - e : 0;
    return lb < v ? static_cast<std::uint32_t>(lb) : v;
  }
};

}  // namespace lattice
}  // namespace amha
