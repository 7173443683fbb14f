// The lattice search problem: paged dense state index, successors, heuristics.
#include "amha_planner/lattice/detail/lattice_problem.h"

#include "amha_planner/lattice/detail/backward_bound.h"
#include "amha_planner/lattice/detail/goal_reachability.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace amha {
namespace lattice {

LatticeProblem::LatticeProblem(const LatticeGraph& graph,
                               std::shared_ptr<const GoalHeuristics> heuristics, LatticeState start,
                               LatticeState goal, int num_inadmissible, bool backward,
                               bool any_goal_heading, KinematicLookup kinematic)
    : graph_(graph),
      heur_(std::move(heuristics)),
      kinematic_(std::move(kinematic)),
      kinematic_inadmissible_(kinematic_.valid() && graph.config().heuristics.inadmissible ==
                                                        LatticeConfig::Inadmissible::kKinematic),
      num_inadmissible_(std::clamp(num_inadmissible, 0, 3)),
      backward_(backward),
      headings_(graph.numHeadings()),
      keys_(graph.width(), graph.height(), graph.numHeadings(), kVirtualHeading) {
  if (graph.numHeadings() > 0xFFFF)
    throw LatticeError(LatticeError::Kind::kConfig, "too many headings");
  for (int k = 0; k < kNumGridKinds; ++k)
    grids_[k] = heur_ && heur_->grids[k] ? heur_->grids[k].get() : nullptr;
  if (heur_ && heur_->coarse_lattice != nullptr && !heur_->coarse.empty())
    coarse_ = heur_->coarse.data();
  for (int k = 1; k <= num_inadmissible_; ++k) {
    if (grids_[k] == nullptr) num_inadmissible_ = k - 1;  // the planner did not build that grid
  }
  // A grid equal to an earlier one (the same distances at the same scale, e.g. the openings of
  // a robot that fits everywhere its centre does) would be a second copy of one heuristic. The
  // paper's set keeps its copies, so that its results stay as they were.
  const bool dedupe =
      graph.config().heuristics.inadmissible == LatticeConfig::Inadmissible::kKinematic;
  int kept = 0;
  for (int k = 1; k <= num_inadmissible_; ++k) {
    bool copy = false;
    if (!dedupe) {
      grids_[++kept] = grids_[k];
      scale_[kept] = heur_->scale[k];
      continue;
    }
    for (int j = 1; j <= kept; ++j)
      copy = copy || (grids_[j] == grids_[k] && scale_[j] == heur_->scale[k]);
    if (copy) continue;
    ++kept;
    grids_[kept] = grids_[k];
    scale_[kept] = heur_->scale[k];
  }
  num_inadmissible_ = kept;
  // Grids complete already (a problem built after waiting for them) are read without checks.
  grids_complete_ = std::all_of(grids_, grids_ + kNumGridKinds,
                                [](const DistanceGrid* g) { return !g || g->complete(); });
  // Inflation bases only where a heading-aware term is there to be counted once.
  const bool turn_terms =
      graph.config().heuristics.anchor_turn_term && !(any_goal_heading && !backward);
  bases_ = !graph.config().heuristics.inflate_heading_terms && grids_[0] != nullptr &&
           (coarse_ != nullptr || kinematic_.valid() || turn_terms);
  tiles_x_ = (graph.width() + kTile - 1) / kTile;
  const int tiles_y = (graph.height() + kTile - 1) / kTile;
  pages_.assign(static_cast<std::size_t>(tiles_x_) * tiles_y, nullptr);
  page_entries_ = static_cast<std::size_t>(kTile) * kTile * headings_;
  // Searching backward, the heuristics measure from the lattice start, which `goal` is.
  const LatticeState lattice_goal = backward ? start : goal;
  goal_x_ = goal.x;
  goal_y_ = goal.y;
  const std::vector<double>& angles = graph.primitives().heading_angles;
  // A goal of any heading has no heading to turn to (backward, the turn is to the lattice
  // start's heading, which is fixed).
  const bool turn_term =
      graph.config().heuristics.anchor_turn_term && !(any_goal_heading && !backward);
  for (int h = 0; h < headings_; ++h) {
    const double d = turn_term ? angleDistance(angles[h], angles[goal.heading]) : 0.0;
    turn_euclid_.push_back(graph.euclidTurnUnitsPerRadian() * d);
    turn_grid_.push_back(graph.gridTurnUnitsPerRadian() * d * kGridFraction);
  }
  if (!any_goal_heading) {
    start_ = id(start.x, start.y, start.heading);
    goal_ = id(goal.x, goal.y, goal.heading);
    return;
  }
  virtual_goal_ = keys_.add(lattice_goal.x, lattice_goal.y, kVirtualHeading);
  if (backward) {
    start_ = virtual_goal_;
    goal_ = id(goal.x, goal.y, goal.heading);
    for (int h = 0; h < headings_; ++h) {
      if (graph.stateValid(lattice_goal.x, lattice_goal.y, h))
        into_goal_cell_.push_back(Edge{id(lattice_goal.x, lattice_goal.y, h), 0});
    }
  } else {
    start_ = id(start.x, start.y, start.heading);
    goal_ = virtual_goal_;
  }
}

LatticeProblem::~LatticeProblem() = default;

StateId LatticeProblem::id(int x, int y, int heading) {
  const std::size_t tile = tileOf(x, y);
  std::uint32_t* page = pages_[tile];
  if (page == nullptr) {
    if (slabs_.empty() || slab_used_ == kPagesPerSlab) {
      slabs_.emplace_back(new std::uint32_t[kPagesPerSlab * page_entries_]);
      slab_used_ = 0;
    }
    page = slabs_.back().get() + slab_used_++ * page_entries_;
    std::fill(page, page + page_entries_, kNoState);
    pages_[tile] = page;
  }
  std::uint32_t& slot = page[slotInPage(x, y, heading)];
  if (slot == kNoState) {
    slot = keys_.add(x, y, heading);
  }
  return slot;
}

void LatticeProblem::prefetchId(int x, int y, int heading) const {
  if (x < 0 || y < 0 || x >= tiles_x_ * kTile) return;  // off the map: edgeCost refuses it
  const std::size_t tile = tileOf(x, y);
  if (tile >= pages_.size() || pages_[tile] == nullptr) return;
  __builtin_prefetch(pages_[tile] + slotInPage(x, y, heading));
}

void LatticeProblem::successors(StateId s, std::vector<Edge>& out) {
  out.clear();
  if (s == virtual_start_) {  // a start in collision: on to each exit, at its escape cost
    out = start_exits_;
    return;
  }
  if (s == virtual_goal_) {  // forward: the end; backward: the start, joined to the goal's cell
    if (backward_) out = into_goal_cell_;
    return;
  }
  const LatticeState st = state(s);
  // The successors' index slots are cache misses in pages of 4 kB: start loading them all
  // before the edges' collision tests, which have misses of their own.
  if (backward_) {
    for (const LatticeAction* a : graph_.actionsInto(st.heading)) {
      prefetchId(st.x - a->dx, st.y - a->dy, a->start_heading);
    }
    for (const LatticeAction* a : graph_.actionsInto(st.heading)) {
      const int x = st.x - a->dx, y = st.y - a->dy;
      const Cost c = graph_.edgeCost(x, y, *a);  // checks that (x, y) and the motion are in the map
      if (c == kInvalidEdge) continue;
      out.push_back(Edge{id(x, y, a->start_heading), c, graph_.actionIndex(a)});
    }
    return;
  }
  for (const LatticeAction* a = graph_.actionsBegin(st.heading); a != graph_.actionsEnd(st.heading);
       ++a) {
    prefetchId(st.x + a->dx, st.y + a->dy, a->end_heading);
  }
  for (const LatticeAction* a = graph_.actionsBegin(st.heading); a != graph_.actionsEnd(st.heading);
       ++a) {
    const Cost c = graph_.edgeCost(st.x, st.y, *a);
    if (c == kInvalidEdge) continue;
    out.push_back(Edge{id(st.x + a->dx, st.y + a->dy, a->end_heading), c, graph_.actionIndex(a)});
  }
  // Any heading at the goal's cell will do: on to the virtual goal, free (the search core allows
  // cost 0 on edges that lie on no cycle: nothing leaves the virtual goal).
  if (virtual_goal_ != kNoState && st.x == goal_x_ && st.y == goal_y_)
    out.push_back(Edge{virtual_goal_, 0});
}

bool LatticeProblem::goalUnreachable(std::size_t budget) {
  if (virtual_start_ != kNoState) return false;  // several starts, joined by escape edges
  // The search's goal: a lattice state, or (a goal of any heading, forward) every state of the
  // goal's cell, which the virtual goal is joined to. Searching backward that goal is the
  // lattice start, and the walk follows the edges forward, toward the lattice goal.
  std::vector<LatticeState> seeds;
  if (goal_ == virtual_goal_) {
    const LatticeState cell = state(virtual_goal_);
    for (int h = 0; h < headings_; ++h) seeds.push_back(LatticeState{cell.x, cell.y, h});
  } else {
    seeds.push_back(state(goal_));
  }
  const LatticeState start = state(start_);
  const bool any_heading = start_ == virtual_goal_;  // backward to a goal of any heading
  auto is_start = [&](const LatticeState& s) {
    return s.x == start.x && s.y == start.y && (any_heading || s.heading == start.heading);
  };
  std::size_t visited = 0;
  if (exploreReachable(graph_, seeds, !backward_, is_start, budget, interrupted_, &visited) !=
      Reachability::kEnclosed)
    return false;
  enclosed_states_ = visited;
  return true;
}

void LatticeProblem::startAtExits(const std::vector<std::pair<LatticeState, Cost>>& exits) {
  if (backward_) throw std::logic_error("LatticeProblem::startAtExits: forward searches only");
  if (exits.empty()) throw std::logic_error("LatticeProblem::startAtExits: no exit");
  start_exits_.clear();
  std::size_t best = 0;
  double best_f = INFINITY;
  for (std::size_t k = 0; k < exits.size(); ++k) {
    const LatticeState& e = exits[k].first;
    start_exits_.push_back(Edge{id(e.x, e.y, e.heading), exits[k].second});
    const HeuristicValue h = anchor(e.x, e.y, e.heading);
    const double f =
        static_cast<double>(exits[k].second) + (h == kInfiniteHeuristic ? INFINITY : h);
    if (f < best_f) {
      best_f = f;
      best = k;
    }
  }
  // Not in the paged index: a state of its own, which state() reads as that exit.
  const LatticeState& e = exits[best].first;
  virtual_start_ = keys_.add(e.x, e.y, e.heading);
  start_ = virtual_start_;
}

HeuristicValue LatticeProblem::anchor(int x, int y, int heading, HeuristicValue* base) const {
  const double dx = x - goal_x_, dy = y - goal_y_;
  const double euclid = graph_.euclidUnitsPerCell() * std::sqrt(dx * dx + dy * dy);
  if (base != nullptr) *base = 0;
  if (grids_[0] == nullptr) {
    const auto e = static_cast<HeuristicValue>(std::min(std::floor(euclid), 4e9));
    if (base != nullptr) *base = e;
    return e;
  }
  const std::uint32_t g = gridAt(0, x, y);
  if (g == kUnreachable) return kInfiniteHeuristic;  // provably cannot reach the goal
  const double a = std::floor(euclid + turn_euclid_[heading]);
  const double b = std::floor((g + turn_grid_[heading]) / kGridFraction);
  double c = 0.0;
  if (coarse_ != nullptr) {
    const std::uint32_t v = coarse_[heur_->coarse_lattice->index(x, y, heading)];
    if (v == kUnreachable) return kInfiniteHeuristic;  // the abstraction proves it unreachable
    c = v;
  }
  // The displacement grid, once complete (upgradeHeuristics): heading-blind, in cost units.
  double d = 0.0;
  if (disp_ != nullptr) {
    const std::uint32_t v = disp_->at(x, y);
    if (v == DisplacementGrid::kUnreachable) return kInfiniteHeuristic;  // no move reaches it
    d = v;
  }
  // The heading-blind part: consistent, as a maximum of consistent terms, and <= the anchor.
  if (base != nullptr)
    *base = static_cast<HeuristicValue>(
        std::min(std::max({std::floor(euclid), std::floor(g / kGridFraction), d}), 4e9));
  if (kinematic_.valid())
    c = std::max<double>(c, kinematic_.value(x - goal_x_, y - goal_y_, heading));
  double rest = std::max({a, b, c, d});
  // The backward search at snapshot K: min(h*, K - e_b) (backward_bound.h). Where K - e_b is
  // not above the rest, neither is the minimum: the closed entry is not read.
  if (backward_key_ != 0 && heading >= 0 && heading < headings_) {
    const BackwardBound& bb = *backward_bound_;
    const HeuristicValue eb = bb.start_anchor->anchor(x, y, heading);
    const double lb = static_cast<double>(backward_key_) - static_cast<double>(eb);
    if (eb != kInfiniteHeuristic && lb > rest) {
      const std::uint32_t v =
          __atomic_load_n(bb.closed.data() + bb.index(x, y, heading), __ATOMIC_RELAXED);
      rest = v != 0 ? std::max(rest, std::min(lb, v - 1.0)) : lb;
    }
  }
  return static_cast<HeuristicValue>(std::min(rest, 4e9));
}

bool LatticeProblem::upgradeHeuristics() {
  bool changed = false;
  if (disp_ == nullptr && displacement_ && grids_[0] != nullptr &&
      displacement_->ready.load(std::memory_order_acquire)) {
    disp_ = displacement_.get();
    changed = true;
  }
  if (backward_bound_ && backward_bound_->ready.load(std::memory_order_acquire)) {
    // Acquire: the states closed before this key are visible to the anchor's reads.
    const std::uint64_t k = backward_bound_->key.load(std::memory_order_acquire);
    if (k > backward_key_ && (backward_key_ == 0 || static_cast<double>(k - backward_key_) >=
                                                        kBackwardStep * backward_key_)) {
      backward_key_ = k;
      changed = true;
    }
  }
  return changed;
}

void LatticeProblem::expanded(StateId s, Cost g, double key) {
  if (s == virtual_goal_ || s == virtual_start_) return;
  const LatticeState st = state(s);
  BackwardBound& bb = *sink_;
  // Every state with a smaller key is closed (A*, e_b consistent): publish the key first
  // (release, after those states' stores), then close this one, whose h* is g.
  const auto k = static_cast<std::uint64_t>(key);
  if (k > bb.key.load(std::memory_order_relaxed)) bb.key.store(k, std::memory_order_release);
  __atomic_store_n(bb.closed.data() + bb.index(st.x, st.y, st.heading),
                   static_cast<std::uint32_t>(std::min<Cost>(g, 0xFFFFFFFEu) + 1),
                   __ATOMIC_RELAXED);
  if (k >= bb.bound.load(std::memory_order_relaxed)) bb.stop.store(true, std::memory_order_relaxed);
}

void LatticeProblem::heuristics(StateId s, HeuristicValue* h, std::size_t count) {
  if (s == virtual_goal_) {  // the goal, or searching backward the start: 0 is exact, or admissible
    for (std::size_t i = 0; i < count; ++i) h[i] = 0, last_bases_[i] = 0;
    return;
  }
  if (!grids_complete_) {
    grids_complete_ = true;
    for (const DistanceGrid* g : grids_) grids_complete_ = grids_complete_ && (!g || g->complete());
  }
  const LatticeState st = state(s);
  h[0] = anchor(st.x, st.y, st.heading, &last_bases_[0]);
  // The inadmissible ones: each Dijkstra, with the kinematic table (kKinematic) the larger of
  // it and the table, as Smac combines its obstacle and distance heuristics.
  const double k = count > 1 && kinematic_inadmissible_
                       ? kinematic_.value(st.x - goal_x_, st.y - goal_y_, st.heading)
                       : 0.0;
  for (std::size_t i = 1; i < count; ++i) {
    const std::uint32_t g = gridAt(static_cast<int>(i), st.x, st.y);
    if (g == kUnreachable) {
      h[i] = kInfiniteHeuristic;
      last_bases_[i] = 0;
      continue;
    }
    const double d = g * scale_[i] / kGridFraction;  // the Dijkstra: the inflation base
    h[i] = static_cast<HeuristicValue>(std::min(std::max(k, d), 4e9));
    last_bases_[i] = static_cast<HeuristicValue>(std::min(d, 4e9));
  }
}

std::size_t LatticeProblem::memoryBytes() const {
  return keys_.bytes() + pages_.capacity() * sizeof(std::uint32_t*) +
         slabs_.size() * kPagesPerSlab * page_entries_ * sizeof(std::uint32_t);
}

}  // namespace lattice
}  // namespace amha
