// Basic types shared by every search algorithm and every domain.
#pragma once

#include <cstdint>
#include <limits>

namespace amha {

/// Dense state identifier: a domain numbers the states it creates 0, 1, 2, ... in discovery
/// order, so the search can keep its per-state data in flat arrays instead of node maps.
using StateId = std::uint32_t;
constexpr StateId kNoState = std::numeric_limits<StateId>::max();

/// Path and edge costs are integers (domains choose a fixed-point unit) so that costs add
/// exactly and "cost == sum of edges" can be tested without tolerances.
using Cost = std::int64_t;
constexpr Cost kInfiniteCost = std::numeric_limits<Cost>::max() / 4;

/// Heuristic values are stored compactly (4 bytes a state and heuristic). A domain must keep
/// finite values below kInfiniteHeuristic; kInfiniteHeuristic itself means "cannot reach the goal"
/// (for the anchor: provably; for an inadmissible heuristic: in its own opinion).
using HeuristicValue = std::uint32_t;
constexpr HeuristicValue kInfiniteHeuristic = std::numeric_limits<HeuristicValue>::max();

/// An edge of the search graph. Costs must be >= 1: positive costs keep parent chains acyclic.
/// The one exception is a cost of 0 on an edge that lies on no cycle (into a state with no
/// successors, or out of one with no predecessors, as the lattice's virtual goal).
/// An edge without a label.
constexpr std::uint32_t kNoLabel = std::numeric_limits<std::uint32_t>::max();

struct Edge {
  StateId to = kNoState;
  /// The domain's name for the edge (the lattice's action), handed back with each solution
  /// (Solution::edge_labels) so that the domain need not look its edges up again.
  std::uint32_t label = kNoLabel;
  Cost cost = 0;

  Edge() = default;
  Edge(StateId to_state, Cost edge_cost, std::uint32_t edge_label = kNoLabel)
      : to(to_state), label(edge_label), cost(edge_cost) {}
};

}  // namespace amha
