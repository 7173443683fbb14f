// A turn-aware admissible heuristic: the exact cost-to-go on an abstraction of the lattice.
// Cells are grouped into k x k blocks; an abstract state is (block, heading). Every lattice
// edge (x, y, h) -> (x + dx, y + dy, h') maps to the abstract edge (block, h) -> (block', h'),
// whose cost is the edge's base cost with the cell-cost factor of the cheapest passable cell
// of the two blocks (a lower bound on the real edge's cost, whose worst centre cell is at least
// as costly as its start and end cells). A path on the lattice maps to a path on the
// abstraction that costs no more, so the abstraction's distance to the goal's (block, heading)
// is admissible and consistent. Unlike the 2-D grids it knows that turning costs: on maps where
// turns are expensive (SBPL's cubicle with 20 s per 45 degrees) it is far more informed.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "amha_planner/lattice/lattice_config.h"
#include "amha_planner/search/stop_condition.h"

namespace amha {
namespace lattice {

class LatticeGraph;
namespace detail {
class RadixHeap;
}

class CoarseLattice {
 public:
  /// block: cells per block side (>= 1; 0 = the smallest >= 2 giving at most 250k abstract states).
  CoarseLattice(const LatticeGraph& graph, int block);
  /// The abstraction of `graph`, whose costs differ from previous's graph's only in `changed`:
  /// the previous one's edges and blocks, with the blocks that meet `changed` recomputed.
  CoarseLattice(const CoarseLattice& previous, const LatticeGraph& graph, const CellRect& changed);

  int block() const { return k_; }
  /// Distances (cost units) of every abstract state to the goal's (forward = false), or from
  /// the start's (forward = true, for backward search), kUnreachable where there is no path.
  /// heading kAnyHeading: to (or from) the nearest of the block's states, whatever their
  /// heading. Empty if `stop` asked to stop first.
  std::vector<std::uint32_t> distances(int x, int y, int heading, bool forward = false,
                                       const StopCondition* stop = nullptr) const;
  /// The same distances, repaired from `old`: distances() of an abstraction whose map differed
  /// from this one's only inside the rectangles `changed` (as HeuristicGridBuilder::repair does
  /// for the grids: only the states near the change, and those whose shortest path crossed
  /// it, are visited). Empty if `stop` asked to stop first.
  std::vector<std::uint32_t> repairDistances(std::vector<std::uint32_t> old,
                                             const std::vector<CellRect>& changed, int x, int y,
                                             int heading, bool forward = false,
                                             const StopCondition* stop = nullptr) const;
  /// Index of the abstract state of lattice state (x, y, heading) in distancesTo's result.
  std::size_t index(int x, int y, int heading) const {
    return (static_cast<std::size_t>(y / k_ + pad_) * pw_ + (x / k_ + pad_)) * headings_ + heading;
  }

 private:
  struct AbstractEdge {
    std::int64_t node_offset;   // other node index - node index
    std::int64_t block_offset;  // other block index - block index
    std::int64_t base_cost;
  };
  /// The first node of the goal's abstract states and how many there are (consecutive).
  std::pair<std::size_t, std::size_t> goalNodes(int x, int y, int heading) const;
  /// Recomputes the blocks that hold cells of `cells`.
  void fillBlocks(const CellRect& cells);
  /// The cost of edge e between nodes whose blocks are vb and vb + e.block_offset, or
  /// kUnreachable if either block is impassable.
  std::uint32_t edgeCost(std::size_t vb, const AbstractEdge& e) const;
  /// Dijkstra from the nodes already in `heap` (their distances in dist); false if stopped.
  bool propagate(const std::vector<std::vector<AbstractEdge>>& edges,
                 std::vector<std::uint32_t>& dist, detail::RadixHeap& heap,
                 const StopCondition* stop) const;

  const LatticeGraph& graph_;
  int k_ = 1, headings_ = 1, pad_ = 0, pw_ = 0, ph_ = 0;
  std::vector<std::uint8_t> block_cost_;            // padded; cheapest passable cell, 255 = none
  std::vector<std::vector<AbstractEdge>> reverse_;  // per end heading: to the predecessors
  std::vector<std::vector<AbstractEdge>> forward_;  // per start heading: to the successors
};

}  // namespace lattice
}  // namespace amha
