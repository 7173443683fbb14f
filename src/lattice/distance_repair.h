// Repair of shortest distances to a goal (or to a few goal nodes, numbered consecutively) after
// some edge costs changed (a dynamic
// shortest-path update in two waves, as in LPA* or dynamic brushfire), shared by the heuristic
// grids and the block abstraction. Exact: the result is what a fresh Dijkstra gives.
//  1. Raise: a node's old distance still holds if some predecessor that kept its own reaches it
//     over an edge of the new graph at exactly that distance. Only the nodes near the change
//     (whose edges may cost something else now) and the nodes that relied on a node found not
//     to hold can fail; they are visited in increasing old distance, so every predecessor is
//     decided first (edges cost at least 1), and those that fail become unreachable.
//  2. Lower: Dijkstra from every node near the change and every predecessor of a failed node,
//     with their distances, which are all reachable on the new graph: it lowers what the change
//     shortened and fills the failed nodes in again.
// "Predecessor" follows the search's relaxation: dist[v] <= dist[u] + cost(u -> v) makes u a
// predecessor of v. Saturated distances (kUnreachable - 1) break the equality test: the callers
// compute those afresh.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "amha_planner/lattice/detail/heuristic_grids.h"
#include "radix_heap.h"

namespace amha {
namespace lattice {
namespace detail {

/// Distances held as they are (the block abstraction's).
struct PlainCells {
  std::uint32_t* dist;
  std::uint32_t get(std::uint32_t v) const { return dist[v]; }
  void set(std::uint32_t v, std::uint32_t d) const { dist[v] = d; }
};
/// Distances held encoded (a heuristic grid's cells, encodeDistance).
struct EncodedCells {
  std::uint32_t* stored;
  std::uint32_t get(std::uint32_t v) const { return decodeDistance(stored[v]); }
  void set(std::uint32_t v, std::uint32_t d) const { stored[v] = encodeDistance(d); }
};

/// `cells` (PlainCells, EncodedCells) holds the old distances, and receives the new ones (in
/// place). forNear(f) calls f(node)
/// for every node near the change; holds(node) is the raise test above (false for a node that
/// is now impassable; true for a goal node if it is passable); forSuccessors(node, f) and
/// forPredecessors(node, f) call f(other) along the relaxation's edges, out of and into node;
/// propagate(queue) runs the Dijkstra of a fresh computation from the nodes in `queue` and
/// returns false if stopped. The goal nodes are goal .. goal + goal_count - 1 (distance 0);
/// goal_open: they are passable (sources again if they were not).
/// Returns false if `stop` asked to stop (dist is then incomplete); `lower` receives the last
/// key the second wave popped.
template <class Cells, class ForNear, class Holds, class ForSuccessors, class ForPredecessors,
          class Propagate>
bool repairDistances(Cells cells, std::uint32_t goal, std::uint32_t goal_count, bool goal_open,
                     ForNear&& forNear, Holds&& holds, ForSuccessors&& forSuccessors,
                     ForPredecessors&& forPredecessors, Propagate&& propagate,
                     const StopCondition* stop, RadixHeap& lower) {
  std::vector<std::uint32_t> failed;
  {
    RadixHeap raise;
    forNear([&](std::uint32_t v) {
      const std::uint32_t d = cells.get(v);
      if (d != kUnreachable) raise.push(d, v);
    });
    for (std::uint32_t pops = 0; !raise.empty();) {
      // Not a structured binding: clang before 16 cannot capture one in the lambda below.
      const std::pair<std::uint32_t, std::uint32_t> top = raise.pop();
      const std::uint32_t d = top.first, v = top.second;
      if (d != cells.get(v)) continue;  // failed already
      if ((++pops & 1023) == 0 && stop != nullptr && stop->requested()) return false;
      if (holds(v)) continue;
      cells.set(v, kUnreachable);
      failed.push_back(v);
      forSuccessors(v, [&](std::uint32_t t) {
        const std::uint32_t dt = cells.get(t);
        if (dt != kUnreachable && dt > d) raise.push(dt, t);
      });
    }
  }
  for (std::uint32_t v = goal; goal_open && v < goal + goal_count; ++v) {
    if (cells.get(v) != 0) {
      cells.set(v, 0);
      lower.push(0, v);
    }
  }
  forNear([&](std::uint32_t v) {
    const std::uint32_t d = cells.get(v);
    if (d != kUnreachable) lower.push(d, v);
  });
  for (const std::uint32_t v : failed) {
    forPredecessors(v, [&](std::uint32_t u) {
      const std::uint32_t d = cells.get(u);
      if (d != kUnreachable) lower.push(d, u);
    });
  }
  return propagate(lower);
}

}  // namespace detail
}  // namespace lattice
}  // namespace amha
