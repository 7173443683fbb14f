// Start escape: a Dijkstra over the states in collision near the start (see start_escape.h).
#include "amha_planner/lattice/detail/start_escape.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>

#include "amha_planner/lattice/detail/heuristic_grids.h"

namespace amha {
namespace lattice {

StartEscape::StartEscape(const LatticeGraph& graph, const LatticeState& start, double tolerance,
                         double penalty, const StopCondition* stop)
    : graph_(graph), penalty_(penalty) {
  const GridMap& map = graph.map();
  // The obstacle cells the robot stands on: under its footprint (its centre cell included).
  std::vector<CellOffset> under{CellOffset{0, 0}};
  if (!graph.footprint().polygon.empty()) {
    under = footprintCells(graph.footprint(),
                           Pose2D{0.0, 0.0, graph.primitives().heading_angles[start.heading]},
                           map.resolution);
  }
  for (const CellOffset& c : under) {
    const int x = start.x + c.dx, y = start.y + c.dy;
    if (x < 0 || y < 0 || x >= map.width || y >= map.height || map.at(x, y) < kLethalCost) continue;
    allowed_.push_back(static_cast<std::int64_t>(y) * map.width + x);
  }
  std::sort(allowed_.begin(), allowed_.end());
  allowed_.erase(std::unique(allowed_.begin(), allowed_.end()), allowed_.end());

  // States within the tolerance: cell centres at most `reach` cells from the start cell's.
  const double reach = tolerance / map.resolution + 1e-9;
  using Item = std::pair<Cost, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
  auto reached = [&](const LatticeState& s, Cost g, std::int64_t parent, const LatticeAction* via) {
    const auto [it, added] = index_.try_emplace(key(s), static_cast<std::uint32_t>(nodes_.size()));
    if (added) {
      nodes_.push_back(Node{s, g, parent, via, false});
    } else {
      Node& n = nodes_[it->second];
      if (n.closed || g >= n.g) return;
      n.g = g;
      n.parent = parent;
      n.via = via;
    }
    open.push({g, it->second});
  };
  reached(start, 0, -1, nullptr);
  while (!open.empty()) {
    if ((expanded_ & 1023u) == 0 && stop != nullptr && stop->requested()) {
      outcome_ = Outcome::kStopped;
      return;
    }
    const auto [g, k] = open.top();
    open.pop();
    if (nodes_[k].closed || g != nodes_[k].g) continue;
    nodes_[k].closed = true;
    const LatticeState s = nodes_[k].state;
    if (graph.stateValid(s.x, s.y, s.heading)) {  // left the collision: an exit, not expanded
      exit_index_.emplace(key(s), exits_.size());
      exits_.push_back(Exit{s, g, k});
      continue;
    }
    ++expanded_;
    for (const LatticeAction* a = graph.actionsBegin(s.heading); a != graph.actionsEnd(s.heading);
         ++a) {
      const LatticeState t{s.x + a->dx, s.y + a->dy, a->end_heading};
      if (std::hypot(t.x - start.x, t.y - start.y) > reach) continue;
      const Cost c = motionCost(s.x, s.y, *a);
      if (c != kInvalidEdge) reached(t, g + c, k, a);
    }
  }
  outcome_ = exits_.empty() ? Outcome::kNoExit : Outcome::kFound;
}

bool StartEscape::allowed(std::int64_t cell) const {
  return std::binary_search(allowed_.begin(), allowed_.end(), cell);
}

std::uint64_t StartEscape::key(const LatticeState& s) const {
  return (static_cast<std::uint64_t>(s.y) * graph_.width() + s.x) << 16 |
         static_cast<std::uint64_t>(s.heading);
}

Cost StartEscape::motionCost(int x, int y, const LatticeAction& a) const {
  const GridMap& map = graph_.map();
  if (x + a.min_dx < 0 || x + a.max_dx >= map.width || y + a.min_dy < 0 ||
      y + a.max_dy >= map.height) {
    return kInvalidEdge;
  }
  const std::int64_t base = static_cast<std::int64_t>(y) * map.width + x;
  const std::vector<std::int64_t>& offsets = graph_.offsets();
  for (std::uint32_t k = a.centre_begin; k < a.centre_end; ++k) {
    const std::int64_t cell = base + offsets[k];
    if (map.cost[cell] >= kLethalCost && !allowed(cell)) return kInvalidEdge;  // inscribed is fine
  }
  for (std::uint32_t k = a.swept_begin; k < a.swept_end; ++k) {
    const std::int64_t cell = base + offsets[k];
    if (map.cost[cell] >= kLethalCost && !allowed(cell)) return kInvalidEdge;
  }
  const double cost = penalty_ * static_cast<double>(graph_.costWithPenalty(a.base_cost, 252));
  return std::max<Cost>(1, static_cast<Cost>(std::ceil(cost - 1e-9)));
}

std::vector<StartEscape::Step> StartEscape::path(const Exit& exit) const {
  std::vector<Step> steps;
  for (std::int64_t k = exit.node; nodes_[k].parent >= 0; k = nodes_[k].parent) {
    steps.push_back(Step{nodes_[nodes_[k].parent].state, nodes_[k].via});
  }
  std::reverse(steps.begin(), steps.end());
  return steps;
}

const StartEscape::Exit* StartEscape::exitAt(const LatticeState& state) const {
  const auto it = exit_index_.find(key(state));
  return it == exit_index_.end() ? nullptr : &exits_[it->second];
}

}  // namespace lattice
}  // namespace amha
