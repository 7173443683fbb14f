// Whether a lattice search's goal can be reached at all, told from the goal's side.
//
// A search that has no path yet can only say "no path" once it has exhausted every state its
// start reaches, which on a large map is millions of states and seconds (and the memory they
// take). Looked at from the other end, the states that can reach the goal are often few: a goal
// pose that no motion ends in is reached by none, a pocket the robot cannot turn into by the few
// thousand inside it. So the search (SearchProblem::goalUnreachable) asks this exploration, with
// a budget of states: it follows the lattice's edges backward from the goal (forward from it,
// for a backward search) until it meets the search's start (no proof), runs out of states
// (a proof: every state that reaches the goal is known, and the start is none of them) or out
// of budget. It tests each edge with the same LatticeGraph::edgeCost as the search's successors,
// so it explores exactly the search's graph, reversed.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "amha_planner/lattice/detail/lattice_problem.h"
#include "amha_planner/lattice/lattice_graph.h"

namespace amha {
namespace lattice {

enum class Reachability {
  kReached,      ///< a target was met: a path may exist
  kEnclosed,     ///< every state connected to the seeds was visited, none a target: no path
  kOverBudget,   ///< more states than the budget: not known
  kInterrupted,  ///< `interrupted` said so: not known
};

/// Explores from `seeds` along the lattice's edges reversed (against_edges: the states each
/// state is reached from) or as they are, looking for a state that `is_target` accepts (a
/// target's heading may be any). Visits at most `budget` states; calls `interrupted`, if given,
/// every 4096 states. With kEnclosed, `visited`, if given, receives how many states are
/// connected to the seeds (all of them visited).
Reachability exploreReachable(const LatticeGraph& graph, const std::vector<LatticeState>& seeds,
                              bool against_edges,
                              const std::function<bool(const LatticeState&)>& is_target,
                              std::size_t budget,
                              const std::function<bool()>& interrupted = nullptr,
                              std::size_t* visited = nullptr);

}  // namespace lattice
}  // namespace amha
