// Goal tolerance, as nav_msgs/GetPlan's `tolerance` means it: when the requested goal pose is
// in collision, plan instead to the nearest collision-free lattice pose within the tolerance
// that the start can provably reach the neighbourhood of.
#pragma once

#include <cstdint>
#include <vector>

#include "amha_planner/lattice/lattice_planner.h"

namespace amha {
namespace lattice {

class LatticeGraph;
struct GridStop;

/// The cells the robot's centre may reach from a start cell: the start's 8-connected component
/// of cells below kInscribedCost. Every valid state and every motion's centre line lies on such
/// cells (LatticeGraph::stateValid, edgeCost), and a centre line is continuous, so a cell
/// outside the component is out of reach of every path; the converse does not hold (the robot
/// may still be too wide or unable to turn), which only makes the test weaker, never wrong.
/// The breadth-first search runs on demand and resumes where it stopped, so any number of
/// questions cost at most one pass over the component.
class CentreReachability {
 public:
  enum class Answer { kYes, kNo, kStopped };
  /// (start_x, start_y) must be a cell of `map`.
  CentreReachability(const GridMap& map, int start_x, int start_y);
  /// Whether (x, y) is in the start's component; kStopped if `stop` (may be null) asked first.
  Answer reaches(int x, int y, const GridStop* stop);

 private:
  const GridMap& map_;
  std::vector<std::uint8_t> seen_;    // per cell: queued at some point
  std::vector<std::int32_t> queue_;   // cell indices in breadth-first order (maps < 2^31 cells)
  std::size_t head_ = 0;              // queue_[head_..] are still to be expanded
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
GoalChoice nearestReachableGoal(const LatticeGraph& graph, const Pose2D& goal, double tolerance, int start_x,
                                int start_y, const GridStop* stop);

}  // namespace lattice
}  // namespace amha
