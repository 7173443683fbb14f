// Reachability from the goal's side (goal_reachability.h): a depth-first walk over the lattice's
// edges with a hash set of visited states; the budget keeps both small.
#include "amha_planner/lattice/detail/goal_reachability.h"

#include <cstdint>
#include <unordered_set>

namespace amha {
namespace lattice {

Reachability exploreReachable(const LatticeGraph& graph, const std::vector<LatticeState>& seeds,
                              bool against_edges,
                              const std::function<bool(const LatticeState&)>& is_target,
                              std::size_t budget, const std::function<bool()>& interrupted,
                              std::size_t* visited_count) {
  const auto headings = static_cast<std::uint64_t>(graph.numHeadings());
  const auto width = static_cast<std::uint64_t>(graph.width());
  auto key = [&](int x, int y, int h) {
    return (static_cast<std::uint64_t>(y) * width + static_cast<std::uint64_t>(x)) * headings +
           static_cast<std::uint64_t>(h);
  };
  std::unordered_set<std::uint64_t> visited;
  std::vector<LatticeState> stack;
  // False once the budget is spent.
  auto visit = [&](const LatticeState& s) {
    if (!visited.insert(key(s.x, s.y, s.heading)).second) return true;
    if (visited.size() > budget) return false;
    stack.push_back(s);
    return true;
  };
  for (const LatticeState& s : seeds) {
    if (s.x < 0 || s.y < 0 || s.x >= graph.width() || s.y >= graph.height() || s.heading < 0 ||
        s.heading >= graph.numHeadings())
      continue;  // not a lattice state: no edge touches it
    if (is_target(s)) return Reachability::kReached;
    if (!visit(s)) return Reachability::kOverBudget;
  }
  std::size_t popped = 0;
  while (!stack.empty()) {
    const LatticeState s = stack.back();
    stack.pop_back();
    if ((++popped & 4095u) == 0 && interrupted && interrupted()) return Reachability::kInterrupted;
    auto step = [&](const LatticeState& next) {
      if (is_target(next)) return Reachability::kReached;
      return visit(next) ? Reachability::kEnclosed : Reachability::kOverBudget;
    };
    if (against_edges) {
      for (const LatticeAction* a : graph.actionsInto(s.heading)) {
        const int x = s.x - a->dx, y = s.y - a->dy;
        if (graph.edgeCost(x, y, *a) == kInvalidEdge) continue;  // also: (x, y) off the map
        const Reachability r = step(LatticeState{x, y, a->start_heading});
        if (r != Reachability::kEnclosed) return r;
      }
    } else {
      for (const LatticeAction* a = graph.actionsBegin(s.heading); a != graph.actionsEnd(s.heading);
           ++a) {
        if (graph.edgeCost(s.x, s.y, *a) == kInvalidEdge) continue;
        const Reachability r = step(LatticeState{s.x + a->dx, s.y + a->dy, a->end_heading});
        if (r != Reachability::kEnclosed) return r;
      }
    }
  }
  if (visited_count != nullptr) *visited_count = visited.size();
  return Reachability::kEnclosed;
}

}  // namespace lattice
}  // namespace amha
