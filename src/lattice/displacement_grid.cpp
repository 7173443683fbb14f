#include "amha_planner/lattice/detail/displacement_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include "amha_planner/lattice/lattice_graph.h"
#include "dial_queue.h"
#include "radix_heap.h"

namespace amha {
namespace lattice {

DisplacementGrid::DisplacementGrid(const LatticeGraph& graph)
    : width_(graph.width()), height_(graph.height()) {
  // One move per displacement: the cheapest base cost, and the centre cells every action with
  // that displacement crosses (a cell one of them avoids cannot be asked of the move).
  std::map<std::pair<int, int>, std::pair<std::int64_t, std::set<std::pair<int, int>>>> by_d;
  const std::vector<LatticeAction>& actions = graph.actions();
  for (std::size_t a = 0; a < actions.size(); ++a) {
    const LatticeAction& act = actions[a];
    if (act.dx == 0 && act.dy == 0) continue;  // a turn on the spot: no move of a cell
    std::set<std::pair<int, int>> cells;
    for (const CellOffset& c : graph.actionCells(a).centre) cells.insert({c.dx, c.dy});
    const auto key = std::make_pair(act.dx, act.dy);
    auto it = by_d.find(key);
    if (it == by_d.end()) {
      by_d.emplace(key, std::make_pair(static_cast<std::int64_t>(act.base_cost), cells));
      continue;
    }
    it->second.first = std::min<std::int64_t>(it->second.first, act.base_cost);
    std::set<std::pair<int, int>> common;
    for (const auto& c : it->second.second) {
      if (cells.count(c)) common.insert(c);
    }
    it->second.second = std::move(common);
  }
  int reach_max = 0;
  for (const auto& [d, v] : by_d) {
    Move m;
    m.dx = d.first;
    m.dy = d.second;
    m.base_cost = v.first;
    m.cells.assign(v.second.begin(), v.second.end());
    m.reach = std::max(std::abs(m.dx), std::abs(m.dy));
    for (const auto& c : m.cells)
      m.reach = std::max({m.reach, std::abs(c.first), std::abs(c.second)});
    reach_max = std::max(reach_max, m.reach);
    moves_.push_back(std::move(m));
  }
  // In memory order (rows, then columns): a cell's relaxations then walk its neighbourhood
  // from one end to the other.
  std::sort(moves_.begin(), moves_.end(),
            [](const Move& a, const Move& b) { return a.dy != b.dy ? a.dy < b.dy : a.dx < b.dx; });
  pad_ = reach_max + 1;  // a needed cell off the map lands on padding (255)
  padded_width_ = width_ + 2 * pad_;
  const std::size_t padded_height = static_cast<std::size_t>(height_ + 2 * pad_);
  needed_begin_.push_back(0);
  // kappa: at most every move's cheapest cost per cell of its length. Then for a move from a to
  // b, e(a) - e(b) < kappa |a - b| + 1 <= step + 1 (the floors), an integer, so at most the
  // step: the guide is consistent. (0.01 below, for the rounding of the square roots.)
  kappa_ = std::numeric_limits<double>::infinity();
  for (const Move& m : moves_) {
    offsets_.push_back(static_cast<std::int64_t>(m.dy) * padded_width_ + m.dx);
    bool start = false, end = false;
    for (const auto& [cx, cy] : m.cells) {
      start = start || (cx == 0 && cy == 0);
      end = end || (cx == m.dx && cy == m.dy);
      if ((cx == 0 && cy == 0) || (cx == m.dx && cy == m.dy)) continue;
      needed_.push_back(static_cast<std::int64_t>(cy) * padded_width_ + cx);
    }
    needed_begin_.push_back(static_cast<std::uint32_t>(needed_.size()));
    reach_.push_back(static_cast<std::uint8_t>(std::min(m.reach, 254)));
    // The penalty is the worst centre cell's: the two ends are centre cells of every action
    // (a primitive starts and ends at its cells' centres), so their worse level is at most that.
    // Were one not (a malformed set), the base cost alone is still a lower bound.
    const bool both_ends = start && end;
    // Indexed by the larger stored level of the two ends (1 + cost; 0 never reaches here).
    for (int l = 0; l < 256; ++l) {
      const unsigned cell = both_ends ? static_cast<unsigned>(std::clamp(l - 1, 0, 252)) : 0u;
      const std::uint64_t cost = graph.costWithPenalty(m.base_cost, cell);
      step_.push_back(static_cast<std::uint32_t>(std::min<std::uint64_t>(cost, kUnreachable - 1)));
      if (l <= kInscribedCost) max_step_ = std::max(max_step_, step_.back());
    }
    const double cheapest = step_[step_.size() - 256 + 1];
    kappa_ = std::min(kappa_, (cheapest - 0.01) / std::hypot(m.dx, m.dy));
  }
  kappa_ = std::isfinite(kappa_) ? std::max(0.0, kappa_) : 0.0;
  // Levels: 1 + the cost of each cell the centre may cross (below inscribed), 0 elsewhere and
  // on the padding, as LatticeGraph::edgeCost tests an action's centre cells. Zero is "blocked"
  // so that wholly blocked pages stay untouched: rows being contiguous, only the rows of unknown
  // above and below a building (3 % of the pages of Willow Garage at 5 and at 2.5 cm).
  level_.reset(static_cast<std::size_t>(padded_width_) * padded_height);
  const std::vector<std::uint8_t>& cost = graph.map().cost;
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const std::uint8_t c = cost[static_cast<std::size_t>(y) * width_ + x];
      if (c < kInscribedCost) level_[index(x, y)] = static_cast<std::uint8_t>(c + 1);
    }
  }
  // Clearance (Chebyshev distance to the nearest blocked cell, two chamfer passes): a move whose
  // cells all lie within its reach of its start needs no test where the start's clearance
  // exceeds that reach. (OpenCV's distanceTransform writes 8-bit images for L1 only, and a
  // float image would take four times the map.) Blocked cells keep 0, unwritten.
  clear_.reset(level_.size());
  const std::size_t pw = static_cast<std::size_t>(padded_width_);
  for (std::size_t i = 0; i < level_.size(); ++i) {
    if (level_[i] != 0) clear_[i] = 255;
  }
  auto relax = [](std::uint8_t& c, std::uint8_t n) {
    if (n + 1 < c) c = static_cast<std::uint8_t>(n + 1);
  };
  for (std::size_t y = 1; y < padded_height; ++y) {
    for (std::size_t x = 1; x + 1 < pw; ++x) {
      std::uint8_t& c = clear_[y * pw + x];
      if (c == 0) continue;
      const std::size_t u = (y - 1) * pw + x;
      relax(c, clear_[u - 1]);
      relax(c, clear_[u]);
      relax(c, clear_[u + 1]);
      relax(c, clear_[y * pw + x - 1]);
    }
  }
  for (std::size_t y = padded_height - 1; y-- > 0;) {
    for (std::size_t x = pw - 2; x >= 1; --x) {
      std::uint8_t& c = clear_[y * pw + x];
      if (c != 0) {
        const std::size_t d = (y + 1) * pw + x;
        relax(c, clear_[d - 1]);
        relax(c, clear_[d]);
        relax(c, clear_[d + 1]);
        relax(c, clear_[y * pw + x + 1]);
      }
    }
  }
}

bool DisplacementGrid::compute(int x, int y, bool to_cell, int toward_x, int toward_y,
                               const std::atomic<std::uint64_t>* bound, DisplacementField* out,
                               const std::atomic<bool>* abandon, const StopCondition* stop) const {
  ZeroedArray<std::uint32_t>& dist = out->dist;  // 1 + distance; 0: not reached
  dist.reset(level_.size());
  out->stride = padded_width_;
  out->origin = dist.data() + index(0, 0);
  out->toward_x = toward_x;
  out->toward_y = toward_y;
  out->stop_key = UINT64_MAX;
  out->kappa = kappa_;
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return true;
  const auto origin = static_cast<std::uint32_t>(index(x, y));
  if (level_[origin] == 0) return true;  // the centre cannot be there: nothing reaches it
  dist[origin] = 1;
  const std::int64_t tx = toward_x + pad_, ty = toward_y + pad_;
  const auto first =
      static_cast<std::uint32_t>(displacementGuide(kappa_, x - toward_x, y - toward_y));
  auto search = [&](auto& queue) {
    queue.push(first, origin);
    return to_cell ? run<true>(dist.data(), queue, tx, ty, bound, &out->stop_key, abandon, stop)
                   : run<false>(dist.data(), queue, tx, ty, bound, &out->stop_key, abandon, stop);
  };
  // A key is at most a step and the change of the guide along it (below a step) above the last
  // popped.
  if (2.0 * max_step_ + first < 4e9 && max_step_ < (1u << 15)) {
    detail::DialQueue q(2 * max_step_, first);
    return search(q);
  }
  detail::RadixHeap q;
  return search(q);
}

// A* from the origin toward (tx, ty) (padded). Toward the origin (kToCell), a settled cell i
// relaxes the start p = i - d of each move that ends there; from it, the end q = i + d of each
// move that starts there. A move from p needs p's and its end's levels below 255 and, unless
// p's clearance exceeds its reach, each of its other cells. Distances saturate at
// kUnreachable - 1: still a lower bound, and the minimum of two consistent functions.
template <bool kToCell, class Queue>
bool DisplacementGrid::run(std::uint32_t* dist, Queue& queue, std::int64_t tx, std::int64_t ty,
                           const std::atomic<std::uint64_t>* bound, std::uint64_t* stop_key,
                           const std::atomic<bool>* abandon, const StopCondition* stop) const {
  const std::size_t nm = offsets_.size();
  const std::uint8_t* level = level_.data();
  const std::uint8_t* clear = clear_.data();
  const std::int64_t* needed = needed_.data();
  const std::int64_t pw = padded_width_;
  // The guide, from a cell's offset to (tx, ty): exactly DisplacementField::at's.
  auto e = [this](std::int64_t dx, std::int64_t dy) {
    return displacementGuide(kappa_, static_cast<double>(dx), static_cast<double>(dy));
  };
  const std::uint32_t upw = static_cast<std::uint32_t>(pw);  // a 32-bit division is faster
  for (std::uint32_t pops = 0; !queue.empty();) {
    const auto [key, i] = queue.pop();
    const std::uint64_t limit =
        bound != nullptr ? bound->load(std::memory_order_relaxed) : UINT64_MAX;
    if (key >= limit) {  // every cell left has a distance of at least key - e
      *stop_key = key;
      return true;
    }
    const std::uint32_t d = dist[i] - 1;
    const std::int64_t ix = static_cast<std::int64_t>(i % upw) - tx;
    const std::int64_t iy = static_cast<std::int64_t>(i / upw) - ty;
    if (static_cast<std::uint64_t>(d) + e(ix, iy) != key) continue;  // stale
    if ((++pops & 4095) == 0) {
      if (abandon != nullptr && abandon->load(std::memory_order_relaxed)) return false;
      if (stop != nullptr && stop->requested()) return false;
    }
    const unsigned li = level[i];
    for (std::size_t m = 0; m < nm; ++m) {
      const std::size_t j = kToCell ? i - offsets_[m] : i + offsets_[m];
      // A move can lower only a distance above d plus its cheapest cost: most neighbours of a
      // settled cell are settled already, so this test saves the others for the few left.
      // (A stored 0, not reached, is 2^32 - 1 less one: above any distance.)
      if (dist[j] - 1u <= static_cast<std::uint64_t>(d) + step_[m * 256]) continue;
      const unsigned lj = level[j];
      if (lj == 0) continue;
      const std::size_t from = kToCell ? j : i;  // the move's start cell
      if (clear[from] <= reach_[m]) {
        bool free = true;
        for (std::uint32_t k = needed_begin_[m]; k < needed_begin_[m + 1]; ++k) {
          if (level[static_cast<std::size_t>(static_cast<std::int64_t>(from) + needed[k])] == 0) {
            free = false;
            break;
          }
        }
        if (!free) continue;
      }
      const std::uint64_t nd = static_cast<std::uint64_t>(d) + step_[m * 256 + std::max(li, lj)];
      const auto v = static_cast<std::uint32_t>(std::min<std::uint64_t>(nd, kUnreachable - 1));
      if (v < dist[j] - 1u) {
        dist[j] = v + 1;
        const std::int64_t jx = kToCell ? ix - moves_[m].dx : ix + moves_[m].dx;
        const std::int64_t jy = kToCell ? iy - moves_[m].dy : iy + moves_[m].dy;
        queue.push(static_cast<std::uint32_t>(std::min<std::uint64_t>(v + e(jx, jy), 0xFFFFFFFFu)),
                   static_cast<std::uint32_t>(j));
      }
    }
  }
  return true;
}

}  // namespace lattice
}  // namespace amha
