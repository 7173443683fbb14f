// Goal tolerance: the nearest collision-free, reachable lattice state to an obstructed goal.
#include "amha_planner/lattice/detail/goal_tolerance.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <tuple>

#include "amha_planner/lattice/detail/heuristic_grids.h"
#include "amha_planner/lattice/lattice_graph.h"

namespace amha {
namespace lattice {

CentreReachability::CentreReachability(const GridMap& map, int start_x, int start_y)
    : map_(map),
      start_(start_y * map.width + start_x),
      from_start_((static_cast<std::size_t>(map.width) * map.height + 63) / 64, 0),
      from_cell_(from_start_.size(), 0),
      unreachable_(from_start_.size(), 0) {
  start_side_.target = start_;
  if (map.cost[start_] < kInscribedCost) {
    set(from_start_, start_);
    push(start_side_, start_);
  }
}

std::int64_t CentreReachability::distance2(std::int32_t a, std::int32_t b) const {
  const std::int64_t dx = a % map_.width - b % map_.width, dy = a / map_.width - b / map_.width;
  return dx * dx + dy * dy;
}

void CentreReachability::push(Side& side, std::int32_t c) {
  side.heap.emplace_back(distance2(c, side.target), c);
  std::push_heap(side.heap.begin(), side.heap.end(), std::greater<>());
}

void CentreReachability::retarget(Side& side, std::int32_t target) {
  if (side.target == target) return;
  side.target = target;
  for (auto& e : side.heap) e.first = distance2(e.second, target);
  std::make_heap(side.heap.begin(), side.heap.end(), std::greater<>());
}

bool CentreReachability::expand(Side& side, std::vector<std::uint64_t>& mine,
                                const std::vector<std::uint64_t>& other,
                                std::vector<std::int32_t>* touched) {
  std::pop_heap(side.heap.begin(), side.heap.end(), std::greater<>());
  const std::int32_t c = side.heap.back().second;
  side.heap.pop_back();
  const int w = map_.width, h = map_.height;
  const int cx = c % w, cy = c / w;
  bool met = false;
  // Every neighbour is taken even after a meeting: the start's side is kept for later
  // questions, and a cell popped without all its neighbours would leave a hole in it.
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const int nx = cx + dx, ny = cy + dy;
      if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
      const std::int32_t n = ny * w + nx;
      if (test(mine, n) || map_.cost[n] >= kInscribedCost) continue;
      met = met || test(other, n);
      set(mine, n);
      if (touched != nullptr) touched->push_back(n);
      push(side, n);
    }
  }
  return met;
}

CentreReachability::Answer CentreReachability::reaches(int x, int y, const StopCondition* stop) {
  const std::int32_t target = y * map_.width + x;
  if (test(from_start_, target)) return Answer::kYes;
  if (test(unreachable_, target) || map_.cost[target] >= kInscribedCost) return Answer::kNo;
  if (start_side_.heap.empty()) return Answer::kNo;  // the start's whole component is known
  retarget(start_side_, target);
  Side cell_side;
  cell_side.target = start_;
  std::vector<std::int32_t> touched{target};
  set(from_cell_, target);
  push(cell_side, target);
  Answer answer = Answer::kNo;
  for (std::size_t step = 0;; ++step) {
    if ((step & 4095u) == 0 && stop != nullptr && stop->requested()) {
      answer = Answer::kStopped;
      break;
    }
    // The start's side runs out: its component is complete and lacks the cell. The cell's side
    // runs out: the cell's component is complete and lacks the start.
    if (start_side_.heap.empty() || cell_side.heap.empty()) break;
    if (expand(start_side_, from_start_, from_cell_, nullptr) ||
        expand(cell_side, from_cell_, from_start_, &touched)) {
      answer = Answer::kYes;
      break;
    }
  }
  // A side that ran out without meeting the start's is a whole component without the start.
  const bool cell_side_unreachable = answer == Answer::kNo && cell_side.heap.empty();
  for (const std::int32_t c : touched) {
    from_cell_[c >> 6] &= ~(std::uint64_t{1} << (c & 63));
    if (cell_side_unreachable) set(unreachable_, c);
  }
  return answer;
}

namespace {

/// A cell with a collision-free heading, ordered as nearestReachableGoal prefers them.
struct Candidate {
  double distance;
  double heading_difference;
  std::int64_t index;
  int heading;
  bool operator<(const Candidate& o) const {
    return std::tie(distance, heading_difference, index) <
           std::tie(o.distance, o.heading_difference, o.index);
  }
};

}  // namespace

GoalChoice nearestReachableGoal(const LatticeGraph& graph, const Pose2D& goal, double tolerance,
                                int start_x, int start_y, const StopCondition* stop) {
  GoalChoice choice;
  int gx = 0, gy = 0, gh = 0;
  if (!(tolerance >= 0.0) || !graph.poseToState(goal, &gx, &gy, &gh)) return choice;
  const int w = graph.width(), h = graph.height();
  const double res = graph.map().resolution;
  // The goal lies inside its cell, so every cell centre on ring r (Chebyshev distance r from
  // the goal's cell) is at least (r - 1/2) cells from it: rings past tolerance / res + 1/2 hold
  // nothing within the tolerance, and none lies past the map's larger side.
  const int last_ring = static_cast<int>(
      std::min(std::floor(tolerance / res + 0.5), static_cast<double>(std::max(w, h))));

  // The best valid heading of cell (x, y), if its centre is within the tolerance.
  auto consider = [&](int x, int y, std::vector<Candidate>* out) {
    if (x < 0 || y < 0 || x >= w || y >= h || graph.map().at(x, y) >= kInscribedCost) return;
    const Pose2D centre = graph.stateToPose(x, y, 0);
    const double d = std::hypot(centre.x - goal.x, centre.y - goal.y);
    if (d > tolerance) return;
    Candidate best{d, INFINITY, static_cast<std::int64_t>(y) * w + x, -1};
    for (int k = 0; k < graph.numHeadings(); ++k) {
      if (!graph.stateValid(x, y, k)) continue;
      const double diff =
          std::abs(std::remainder(graph.stateToPose(x, y, k).theta - goal.theta, 2.0 * M_PI));
      if (diff < best.heading_difference) {
        best.heading_difference = diff;
        best.heading = k;
      }
    }
    if (best.heading >= 0) out->push_back(best);
  };

  CentreReachability reach(graph.map(), start_x, start_y);
  bool any_free = false;
  std::vector<Candidate> pending;
  // Decides, nearest first, the pending candidates closer than `below` (every cell closer than
  // that has been considered): true once one is chosen or the search must stop.
  auto decide = [&](double below) {
    std::sort(pending.begin(), pending.end());
    std::size_t k = 0;
    for (; k < pending.size() && pending[k].distance < below; ++k) {
      const Candidate& c = pending[k];
      const int cx = static_cast<int>(c.index % w), cy = static_cast<int>(c.index / w);
      const CentreReachability::Answer a = reach.reaches(cx, cy, stop);
      if (a == CentreReachability::Answer::kNo) continue;
      if (a == CentreReachability::Answer::kStopped) {
        choice.outcome = GoalChoice::Outcome::kStopped;
        return true;
      }
      choice.outcome = GoalChoice::Outcome::kFound;
      choice.x = cx;
      choice.y = cy;
      choice.heading = c.heading;
      choice.distance = c.distance;
      choice.heading_difference = c.heading_difference;
      return true;
    }
    pending.erase(pending.begin(), pending.begin() + static_cast<std::ptrdiff_t>(k));
    return false;
  };

  for (int r = 0; r <= last_ring; ++r) {
    if (r > 0 && decide((r - 0.5) * res)) return choice;
    if (stop != nullptr && stop->requested()) {
      choice.outcome = GoalChoice::Outcome::kStopped;
      return choice;
    }
    const std::size_t before = pending.size();
    if (r == 0) {
      consider(gx, gy, &pending);
    } else {
      for (int x = gx - r; x <= gx + r; ++x) {
        consider(x, gy - r, &pending);
        consider(x, gy + r, &pending);
      }
      for (int y = gy - r + 1; y <= gy + r - 1; ++y) {
        consider(gx - r, y, &pending);
        consider(gx + r, y, &pending);
      }
    }
    any_free = any_free || pending.size() > before;
  }
  if (decide(INFINITY)) return choice;
  choice.outcome =
      any_free ? GoalChoice::Outcome::kNoneReachable : GoalChoice::Outcome::kNoFreePose;
  return choice;
}

}  // namespace lattice
}  // namespace amha
