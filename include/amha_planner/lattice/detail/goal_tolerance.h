// Goal tolerance, as nav_msgs/GetPlan's `tolerance` means it: when the requested goal pose is
// in collision, plan instead to the nearest collision-free lattice pose within the tolerance
// that the start can provably reach the neighbourhood of.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "amha_planner/lattice/lattice_config.h"
#include "amha_planner/search/stop_condition.h"

namespace amha {
namespace lattice {

class LatticeGraph;

/// The cells the robot's centre may reach from a start cell: the start's 8-connected component
/// of cells below kInscribedCost. Every valid state and every motion's centre line lies on such
/// cells (LatticeGraph::stateValid, edgeCost), and a centre line is continuous, so a cell
/// outside the component is out of reach of every path; the converse does not hold (the robot
/// may still be too wide or unable to turn), which only makes the test weaker, never wrong.
///
/// Each question runs two greedy searches at once, one from the start towards the cell and one
/// from the cell towards the start, each expanding the frontier cell nearest its target: they
/// meet (yes) or one runs out of cells (no). A cell in a small closed pocket is thus refused
/// after exploring the pocket, not the start's whole component, and a reachable one is usually
/// found along a corridor rather than a disc. What a search learns is kept: the start's side
/// goes on from where it stopped for the next question, and the cells of a refused cell's side
/// are remembered as unreachable.
class CentreReachability {
 public:
  enum class Answer { kYes, kNo, kStopped };
  /// (start_x, start_y) must be a cell of `map`.
  CentreReachability(const GridMap& map, int start_x, int start_y);
  /// Whether (x, y) is in the start's component; kStopped if `stop` (may be null) asked first.
  Answer reaches(int x, int y, const StopCondition* stop);

 private:
  /// A greedy search over the component: a frontier ordered by squared distance to a target.
  struct Side {
    std::vector<std::pair<std::int64_t, std::int32_t>> heap;  // (distance^2, cell), a min-heap
    std::int32_t target = 0;
  };
  static bool test(const std::vector<std::uint64_t>& bits, std::int32_t c) {
    return (bits[c >> 6] >> (c & 63)) & 1u;
  }
  static void set(std::vector<std::uint64_t>& bits, std::int32_t c) {
    bits[c >> 6] |= std::uint64_t{1} << (c & 63);
  }
  std::int64_t distance2(std::int32_t a, std::int32_t b) const;
  void push(Side& side, std::int32_t c);
  void retarget(Side& side, std::int32_t target);
  /// Expands side's nearest frontier cell, marking its new neighbours in `mine`; true if one of
  /// them is in `other` (the two searches met).
  bool expand(Side& side, std::vector<std::uint64_t>& mine, const std::vector<std::uint64_t>& other,
              std::vector<std::int32_t>* touched);

  const GridMap& map_;
  std::int32_t start_ = 0;
  std::vector<std::uint64_t> from_start_;   // cells the start's side has reached (a bit each)
  std::vector<std::uint64_t> from_cell_;    // cells the current question's side has reached
  std::vector<std::uint64_t> unreachable_;  // cells of the sides that ran out without meeting
  Side start_side_;
};

/// What nearestReachableGoal found.
struct GoalChoice {
  enum class Outcome {
    kFound,          ///< x, y, heading hold the chosen state
    kNoFreePose,     ///< no collision-free state has its cell centre within the tolerance
    kNoneReachable,  ///< there are some, but none in the start's component
    kStopped,        ///< `stop` asked to stop first
  };
  Outcome outcome = Outcome::kNoFreePose;
  int x = 0, y = 0, heading = 0;
  double distance = 0.0;            ///< metres from the goal's position to the chosen cell centre
  double heading_difference = 0.0;  ///< radians between goal.theta and the chosen heading
};

/// The collision-free state (LatticeGraph::stateValid) nearest to `goal`: the one whose cell
/// centre is closest to goal's position, at most `tolerance` metres from it, and in the start
/// cell's CentreReachability component; among equally close cells the one whose best valid
/// heading is nearest goal.theta, then the lowest cell index. Cells are visited in rings around
/// the goal's cell and the search stops at the first ring that cannot hold anything closer, so
/// the work grows with the distance to the answer, not with the tolerance. `goal` must be a
/// finite pose inside the map and tolerance >= 0 (infinity: anywhere on the map).
GoalChoice nearestReachableGoal(const LatticeGraph& graph, const Pose2D& goal, double tolerance,
                                int start_x, int start_y, const StopCondition* stop);

}  // namespace lattice
}  // namespace amha
