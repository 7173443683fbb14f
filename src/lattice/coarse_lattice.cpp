// The block abstraction of the lattice and its backward Dijkstra (see coarse_lattice.h).
#include "amha_planner/lattice/coarse_lattice.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "amha_planner/lattice/heuristic_grids.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "radix_heap.h"

namespace amha {
namespace lattice {

namespace {
int floorDiv(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
}  // namespace

CoarseLattice::CoarseLattice(const LatticeGraph& graph, int block) : graph_(graph), headings_(graph.numHeadings()) {
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
      std::uint8_t& b = block_cost_[static_cast<std::size_t>(y / k_ + pad_) * pw_ + (x / k_ + pad_)];
      b = std::min(b, c);
    }
  }
}

std::vector<std::uint32_t> CoarseLattice::distances(int gx, int gy, int gh, bool forward, const GridStop* stop) const {
  const std::vector<std::vector<AbstractEdge>>& edges = forward ? forward_ : reverse_;
  std::vector<std::uint32_t> dist(static_cast<std::size_t>(pw_) * ph_ * headings_, kUnreachable);
  const std::size_t goal = index(gx, gy, gh);
  if (block_cost_[goal / headings_] == 255) return dist;
  detail::RadixHeap heap;
  dist[goal] = 0;
  heap.push(0, static_cast<std::uint32_t>(goal));
  for (std::uint32_t pops = 0; !heap.empty();) {
    const auto [d, v] = heap.pop();
    if (d != dist[v]) continue;
    if ((++pops & 1023) == 0 && stop != nullptr && stop->requested()) return {};
    const std::size_t vb = v / headings_;
    const unsigned cv = block_cost_[vb];
    for (const AbstractEdge& e : edges[v % headings_]) {
      const std::size_t ub = static_cast<std::size_t>(static_cast<std::int64_t>(vb) + e.block_offset);
      const unsigned cu = block_cost_[ub];
      if (cu == 255) continue;
      const std::uint64_t nd = d + static_cast<std::uint64_t>(graph_.costWithPenalty(e.base_cost, std::max(cu, cv)));
      const std::size_t u = static_cast<std::size_t>(static_cast<std::int64_t>(v) + e.node_offset);
      if (nd < dist[u]) {
        dist[u] = static_cast<std::uint32_t>(std::min<std::uint64_t>(nd, kUnreachable - 1));
        heap.push(dist[u], static_cast<std::uint32_t>(u));
      }
    }
  }
  return dist;
}

}  // namespace lattice
}  // namespace amha
