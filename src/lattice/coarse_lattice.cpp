// The block abstraction of the lattice and its backward Dijkstra (see coarse_lattice.h).
#include "amha_planner/lattice/detail/coarse_lattice.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>

#include "amha_planner/lattice/detail/heuristic_grids.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "distance_repair.h"
#include "radix_heap.h"

namespace amha {
namespace lattice {

namespace {
int floorDiv(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
}  // namespace

CoarseLattice::CoarseLattice(const LatticeGraph& graph, int block)
    : graph_(graph), headings_(graph.numHeadings()) {
  const int w = graph.width(), h = graph.height();
  k_ = block;
  if (k_ <= 0) {
    k_ = 1;
    // Smaller blocks are more informed but cost more per goal; measured on SBPL's cubicle,
    // ~250k abstract states is where the heuristic pays for itself best.
    k_ = 2;
    while (static_cast<double>((w + k_ - 1) / k_) * ((h + k_ - 1) / k_) * headings_ > 2.5e5) ++k_;
  }
  // Reverse edges, one per (start heading, block offset) with the cheapest base cost.
  std::map<std::tuple<int, int, int, int>, std::int64_t> cheapest;  // (end h, start h, DX, DY)
  int reach = 0;
  for (const LatticeAction& a : graph.actions()) {
    const int hs = graph.primitives().primitives[a.primitive].start_heading;
    for (int i = 0; i < k_; ++i) {
      for (int j = 0; j < k_; ++j) {
        const int bx = floorDiv(i + a.dx, k_), by = floorDiv(j + a.dy, k_);
        if (bx == 0 && by == 0 && hs == a.end_heading) continue;  // a self-loop
        auto key = std::make_tuple(a.end_heading, hs, bx, by);
        auto it = cheapest.find(key);
        if (it == cheapest.end() || a.base_cost < it->second) cheapest[key] = a.base_cost;
        reach = std::max({reach, std::abs(bx), std::abs(by)});
      }
    }
  }
  pad_ = reach;
  pw_ = (w + k_ - 1) / k_ + 2 * pad_;
  ph_ = (h + k_ - 1) / k_ + 2 * pad_;
  reverse_.assign(headings_, {});
  forward_.assign(headings_, {});
  for (const auto& [key, cost] : cheapest) {
    const auto [he, hs, bx, by] = key;
    const std::int64_t block_offset = static_cast<std::int64_t>(by) * pw_ + bx;
    reverse_[he].push_back({-block_offset * headings_ + (hs - he), -block_offset, cost});
    forward_[hs].push_back({block_offset * headings_ + (he - hs), block_offset, cost});
  }
  block_cost_.assign(static_cast<std::size_t>(pw_) * ph_, 255);
  fillBlocks(CellRect{0, 0, w, h});
}

CoarseLattice::CoarseLattice(const CoarseLattice& previous, const LatticeGraph& graph,
                             const CellRect& changed)
    : graph_(graph),
      k_(previous.k_),
      headings_(previous.headings_),
      pad_(previous.pad_),
      pw_(previous.pw_),
      ph_(previous.ph_),
      block_cost_(previous.block_cost_),
      reverse_(previous.reverse_),
      forward_(previous.forward_) {
  if (!changed.empty()) fillBlocks(changed);
}

void CoarseLattice::fillBlocks(const CellRect& cells) {
  const int w = graph_.width(), h = graph_.height();
  // Whole blocks: a block's cost is the cheapest of all its cells.
  const int x0 = std::max(cells.x0, 0) / k_ * k_, y0 = std::max(cells.y0, 0) / k_ * k_;
  const int x1 = std::min((std::min(cells.x1, w) + k_ - 1) / k_ * k_, w);
  const int y1 = std::min((std::min(cells.y1, h) + k_ - 1) / k_ * k_, h);
  for (int y = y0; y < y1; y += k_) {
    for (int x = x0; x < x1; x += k_) {
      block_cost_[static_cast<std::size_t>(y / k_ + pad_) * pw_ + (x / k_ + pad_)] = 255;
    }
  }
  const GridMap& m = graph_.map();
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const std::uint8_t c = m.cost[static_cast<std::size_t>(y) * w + x];
      if (c >= kInscribedCost) continue;  // the robot's centre cannot be there
      std::uint8_t& b =
          block_cost_[static_cast<std::size_t>(y / k_ + pad_) * pw_ + (x / k_ + pad_)];
      b = std::min(b, c);
    }
  }
}

std::uint32_t CoarseLattice::edgeCost(std::size_t vb, const AbstractEdge& e) const {
  const unsigned cv = block_cost_[vb];
  const unsigned cu =
      block_cost_[static_cast<std::size_t>(static_cast<std::int64_t>(vb) + e.block_offset)];
  if (cu == 255 || cv == 255) return kUnreachable;
  return static_cast<std::uint32_t>(
      std::min<Cost>(graph_.costWithPenalty(e.base_cost, std::max(cu, cv)), kUnreachable - 1));
}

bool CoarseLattice::propagate(const std::vector<std::vector<AbstractEdge>>& edges,
                              std::vector<std::uint32_t>& dist, detail::RadixHeap& heap,
                              const StopCondition* stop) const {
  for (std::uint32_t pops = 0; !heap.empty();) {
    const auto [d, v] = heap.pop();
    if (d != dist[v]) continue;
    if ((++pops & 1023) == 0 && stop != nullptr && stop->requested()) return false;
    const std::size_t vb = v / headings_;
    for (const AbstractEdge& e : edges[v % headings_]) {
      const std::uint32_t w = edgeCost(vb, e);
      if (w == kUnreachable) continue;
      const std::uint64_t nd = static_cast<std::uint64_t>(d) + w;
      const std::size_t u = static_cast<std::size_t>(static_cast<std::int64_t>(v) + e.node_offset);
      if (nd < dist[u]) {
        dist[u] = static_cast<std::uint32_t>(std::min<std::uint64_t>(nd, kUnreachable - 1));
        heap.push(dist[u], static_cast<std::uint32_t>(u));
      }
    }
  }
  return true;
}

std::pair<std::size_t, std::size_t> CoarseLattice::goalNodes(int gx, int gy, int gh) const {
  if (gh == kAnyHeading) return {index(gx, gy, 0), static_cast<std::size_t>(headings_)};
  return {index(gx, gy, gh), 1};
}

std::vector<std::uint32_t> CoarseLattice::distances(int gx, int gy, int gh, bool forward,
                                                    const StopCondition* stop) const {
  std::vector<std::uint32_t> dist(static_cast<std::size_t>(pw_) * ph_ * headings_, kUnreachable);
  const auto [goal, count] = goalNodes(gx, gy, gh);
  if (block_cost_[goal / headings_] == 255) return dist;
  detail::RadixHeap heap;
  for (std::size_t v = goal; v < goal + count; ++v) {
    dist[v] = 0;
    heap.push(0, static_cast<std::uint32_t>(v));
  }
  if (!propagate(forward ? forward_ : reverse_, dist, heap, stop)) return {};
  return dist;
}

// detail::repairDistances on the abstract graph. Predecessors in this search's direction are
// found through the other direction's edge lists, which hold the same edges reversed.
std::vector<std::uint32_t> CoarseLattice::repairDistances(std::vector<std::uint32_t> old,
                                                          const std::vector<CellRect>& changed,
                                                          int gx, int gy, int gh, bool forward,
                                                          const StopCondition* stop) const {
  const std::size_t total = static_cast<std::size_t>(pw_) * ph_ * headings_;
  // Saturated distances break the equality test (every edge costs at least 1).
  if (old.size() != total || std::find(old.begin(), old.end(), kUnreachable - 1) != old.end()) {
    return distances(gx, gy, gh, forward, stop);
  }
  const std::vector<std::vector<AbstractEdge>>& edges = forward ? forward_ : reverse_;
  const std::vector<std::vector<AbstractEdge>>& into = forward ? reverse_ : forward_;
  std::uint32_t* dist = old.data();
  const std::pair<std::size_t, std::size_t> goals = goalNodes(gx, gy, gh);
  const std::uint32_t goal = static_cast<std::uint32_t>(goals.first),
                      goal_count = static_cast<std::uint32_t>(goals.second);
  // Every node of a block within an edge's reach of a changed cell's block: its edges, in and
  // out, may cost something else now (padded block coordinates).
  std::vector<std::array<int, 4>> near;
  for (const CellRect& r : changed) {
    const int x0 = std::max(r.x0, 0), y0 = std::max(r.y0, 0);
    const int x1 = std::min(r.x1, graph_.width()), y1 = std::min(r.y1, graph_.height());
    if (x0 >= x1 || y0 >= y1) continue;
    near.push_back({x0 / k_, y0 / k_, std::min(pw_ - 1, (x1 - 1) / k_ + 2 * pad_),
                    std::min(ph_ - 1, (y1 - 1) / k_ + 2 * pad_)});
  }
  auto forNear = [&](auto&& f) {
    for (const auto& b : near) {
      for (int by = b[1]; by <= b[3]; ++by) {
        for (int bx = b[0]; bx <= b[2]; ++bx) {
          const std::uint32_t node = static_cast<std::uint32_t>((by * pw_ + bx) * headings_);
          for (int h = 0; h < headings_; ++h) f(node + h);
        }
      }
    }
  };
  auto holds = [&](std::uint32_t u) {
    const std::size_t ub = u / headings_;
    if (block_cost_[ub] == 255) return false;
    if (u - goal < goal_count) return true;  // (unsigned: false below goal)
    for (const AbstractEdge& p : into[u % headings_]) {
      const std::uint32_t v = static_cast<std::uint32_t>(u + p.node_offset);
      if (dist[v] == kUnreachable) continue;
      const std::uint32_t w = edgeCost(ub, p);  // the same edge, v -> u, as seen from u
      if (w != kUnreachable && static_cast<std::uint64_t>(dist[v]) + w == dist[u]) return true;
    }
    return false;
  };
  auto along = [&](const std::vector<std::vector<AbstractEdge>>& lists) {
    return [&](std::uint32_t u, auto&& f) {
      for (const AbstractEdge& e : lists[u % headings_])
        f(static_cast<std::uint32_t>(u + e.node_offset));
    };
  };
  auto propagateFrom = [&](detail::RadixHeap& heap) { return propagate(edges, old, heap, stop); };
  detail::RadixHeap heap;
  if (!detail::repairDistances(detail::PlainCells{dist}, goal, goal_count,
                               block_cost_[goal / headings_] != 255, forNear, holds, along(edges),
                               along(into), propagateFrom, stop, heap)) {
    return {};
  }
  if (std::find(old.begin(), old.end(), kUnreachable - 1) != old.end())
    return distances(gx, gy, gh, forward, stop);
  return old;
}

}  // namespace lattice
}  // namespace amha
