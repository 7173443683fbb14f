// The lattice as a SearchProblem: (x, y, heading) states numbered densely in discovery order
// through a paged index over width x height x headings (pages of 8 x 8 cells, allocated on
// first touch), successors from the precomputed actions, heuristics from the goal's grids.
// One instance per search; the LatticeGraph and GoalHeuristics it reads are shared.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "amha_planner/lattice/detail/displacement_grid.h"
#include "amha_planner/lattice/detail/heuristic_grids.h"
#include "amha_planner/lattice/detail/state_keys.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/search/problem.h"

namespace amha {
namespace lattice {

struct BackwardBound;

struct LatticeState {
  int x = 0, y = 0, heading = 0;
  bool operator==(const LatticeState& o) const {
    return x == o.x && y == o.y && heading == o.heading;
  }
};

class LatticeProblem final : public SearchProblem {
 public:
  /// `heuristics` must be for the goal's cell. num_inadmissible: 0..3 grids after the anchor.
  /// backward: the search runs from `start` to `goal` over reversed edges, i.e. the caller
  /// passes the lattice goal as `start` and the lattice start as `goal`; successors() then
  /// returns predecessors with the cost of the forward edge, and the heuristics (computed with
  /// forward distances from the lattice start) estimate the cost from the lattice start.
  /// any_goal_heading: every valid state of the lattice goal's cell is a goal. The search then
  /// runs to (backward: from) a virtual state joined to each of them by an edge of cost 0, whose
  /// id virtualGoal() gives; heuristics must then be for the goal cell with kAnyHeading (the
  /// coarse distances to any of its headings), and the lattice goal's heading is unused.
  /// kinematic: the obstacle-free kinematic table placed at the lattice goal (backward: the
  /// lattice start), KinematicTables::lookup; an invalid lookup leaves it out of the anchor.
  LatticeProblem(const LatticeGraph& graph, std::shared_ptr<const GoalHeuristics> heuristics,
                 LatticeState start, LatticeState goal, int num_inadmissible, bool backward = false,
                 bool any_goal_heading = false, KinematicLookup kinematic = {});
  ~LatticeProblem() override;

  StateId start() const override { return start_; }
  StateId goal() const override { return goal_; }
  void successors(StateId s, std::vector<Edge>& out) override;
  std::size_t numHeuristics() const override {
    return 1 + static_cast<std::size_t>(num_inadmissible_);
  }
  void heuristics(StateId s, HeuristicValue* h, std::size_t count) override;
  /// Unless LatticeConfig::Heuristics::inflate_heading_terms (and only with a heading-aware term in
  /// the anchor): a weight inflates only the heuristics' heading-blind parts, the anchor's larger
  /// of its Euclidean and grid terms and each inadmissible heuristic's Dijkstra.
  bool hasInflationBases() const override { return bases_; }
  bool integerKeys() const override { return true; }
  void bases(StateId s, HeuristicValue* b, std::size_t count) override {
    (void)s;
    for (std::size_t i = 0; i < count; ++i) b[i] = last_bases_[i];
  }
  std::size_t memoryBytes() const override;

  /// Explores from the search's goal against the search's direction (goal_reachability.h), up
  /// to `budget` states: true if every state that reaches the goal is among them and the start
  /// is not. False where it cannot tell, and always for a start that escapes a collision.
  bool goalUnreachable(std::size_t budget) override;
  /// After goalUnreachable() said true: how many lattice states reach the search's goal (a
  /// backward search's: how many the start reaches). 0 before.
  std::size_t enclosedStates() const { return enclosed_states_; }
  void setInterruptCheck(std::function<bool()> check) override { interrupted_ = std::move(check); }

  /// Starts instead at a virtual state joined to each of `exits` (collision-free states, each
  /// with what reaching it costs: the escapes of a start in collision, StartEscape) by an edge
  /// of that cost (>= 1). Forward searches only (std::logic_error otherwise), before searching.
  /// state() of the virtual start is the exit with the least cost + anchor, whose heuristics it
  /// takes: that keeps the anchor admissible and consistent (h(v) <= cost(v, e) + h(e) for every
  /// exit e). A path's virtual start is its first state; it is no lattice state.
  void startAtExits(const std::vector<std::pair<LatticeState, Cost>>& exits);
  StateId virtualStart() const { return virtual_start_; }

  /// The virtual goal state of an any_goal_heading problem, else kNoState. A path's virtual
  /// state (its last, or first searching backward) is no lattice state: state() of it gives the
  /// goal's cell with heading kVirtualHeading.
  StateId virtualGoal() const { return virtual_goal_; }
  static constexpr int kVirtualHeading = 0xFFFF;

  LatticeState state(StateId s) const {
    LatticeState out;
    keys_.at(s, &out.x, &out.y, &out.heading);
    return out;
  }
  std::size_t numStates() const { return keys_.size(); }
  /// The id of a state, creating it if new.
  StateId id(int x, int y, int heading);
  /// Starts loading id(x, y, heading)'s index slot if its page exists (a hint, nothing more).
  void prefetchId(int x, int y, int heading) const;

  /// Anchor value (admissible and consistent): with the grid anchor, the largest of
  /// floor(Euclidean + turning term), floor(grid + turning term), the block abstraction's
  /// cost-to-go and the kinematic table's value; without it, the Euclidean distance alone (the
  /// paper's anchor). See LatticeGraph::computeAnchorScales and kinematic_table.h. `base`, if
  /// given, receives its heading-blind part (hasInflationBases).
  HeuristicValue anchor(int x, int y, int heading, HeuristicValue* base = nullptr) const;

  /// A displacement grid for this problem's goal (backward: from its start) that a helper
  /// thread is computing (displacement_grid.h). Until it is complete the anchor leaves it out;
  /// then upgradeHeuristics() takes it into the anchor and its heading-blind part (the larger of
  /// consistent, admissible terms: both stay so, and no value falls).
  void setDisplacementField(std::shared_ptr<const DisplacementField> field) {
    displacement_ = std::move(field);
  }
  bool upgradeHeuristics() override;

  /// The backward side of a bidirectional proof (backward_bound.h), which a helper thread
  /// fills: once it is ready, upgradeHeuristics() takes a snapshot of its key whenever that
  /// has risen by kBackwardStep of itself, and the anchor then takes max(h_0, h_K).
  void setBackwardBound(std::shared_ptr<const BackwardBound> bound) {
    backward_bound_ = std::move(bound);
  }
  /// This problem is the backward side itself: its search's expansions fill `bound`.
  void setBackwardSink(BackwardBound* bound) { sink_ = bound; }
  bool wantsExpansions() const override { return sink_ != nullptr; }
  void expanded(StateId s, Cost g, double key) override;
  /// The rise of the backward key, relative to the last snapshot, that makes a new one: each
  /// costs the search a renewal of the values it holds (0.2 %: about ten in a proof).
  static constexpr double kBackwardStep = 0.002;

 private:
  const LatticeGraph& graph_;
  std::shared_ptr<const GoalHeuristics> heur_;
  const DistanceGrid* grids_[kNumGridKinds] = {nullptr, nullptr, nullptr,
                                               nullptr};  // distinct ones
  double scale_[kNumGridKinds] = {1.0, 1.0, 1.0, 1.0};    // their scales
  // Whether every grid is complete (DistanceGrid::complete()): then cells are read without
  // at()'s check, a few percent of a search that looks up four grids per successor.
  bool grids_complete_ = false;
  std::uint32_t gridAt(int k, int x, int y) const {
    return grids_complete_ ? grids_[k]->atComplete(x, y) : grids_[k]->at(x, y);
  }
  const std::uint32_t* coarse_ = nullptr;
  KinematicLookup kinematic_;
  std::shared_ptr<const DisplacementField> displacement_;
  const DisplacementField* disp_ = nullptr;  // displacement_, once taken up
  std::shared_ptr<const BackwardBound> backward_bound_;
  std::uint64_t backward_key_ = 0;  // the snapshot K the anchor uses; 0: none yet
  BackwardBound* sink_ = nullptr;
  std::function<bool()> interrupted_;              // the search's limit check, while it runs
  std::size_t enclosed_states_ = 0;                // enclosedStates()
  bool bases_ = false;                             // hasInflationBases()
  HeuristicValue last_bases_[kNumGridKinds] = {};  // the bases of the state heuristics() saw last
  bool kinematic_inadmissible_ = false;            // the inadmissible heuristics take the table too
  int num_inadmissible_;
  bool backward_ = false;
  int headings_;
  int tiles_x_;
  std::size_t page_entries_;
  std::vector<std::uint32_t*> pages_;                    // per 8 x 8 tile, null until touched
  std::vector<std::unique_ptr<std::uint32_t[]>> slabs_;  // page storage, 64 pages a slab
  std::size_t slab_used_ = 0;
  StateKeys keys_;
  StateId start_ = kNoState, goal_ = kNoState, virtual_goal_ = kNoState;
  int goal_x_ = 0, goal_y_ = 0;
  std::vector<Edge> into_goal_cell_;             // backward, any heading: the virtual start's edges
  StateId virtual_start_ = kNoState;             // startAtExits()
  std::vector<Edge> start_exits_;                //   and its edges
  std::vector<double> turn_euclid_, turn_grid_;  // turning terms per heading (cost units)
  static constexpr int kTile = 8;
  // The paged index's layout (id, prefetchId): the page of cell (x, y), and the state's slot in it.
  std::size_t tileOf(int x, int y) const {
    return static_cast<std::size_t>(y / kTile) * tiles_x_ + x / kTile;
  }
  std::size_t slotInPage(int x, int y, int heading) const {
    return static_cast<std::size_t>((y % kTile) * kTile + x % kTile) * headings_ + heading;
  }
  static constexpr std::size_t kPagesPerSlab = 64;
};

}  // namespace lattice
}  // namespace amha
