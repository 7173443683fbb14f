// An independent check of lattice paths: it shares no geometry code with the planner. For each
// step it looks for a primitive of the file/generator joining the two states, rasterises the
// robot's centre path and footprint by brute force (every cell of a bounding box tested
// against the segment/polygon, the footprint at very densely interpolated poses), checks the
// cells, and recomputes the documented edge cost.
#pragma once

#include <string>
#include <vector>

#include "amha_planner/lattice/detail/lattice_problem.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/lattice/motion_primitives.h"
#include "amha_planner/lattice/path_smoother.h"

namespace amha {
namespace lattice {
namespace test {

struct ValidatorModel {
  const GridMap* map = nullptr;
  const PrimitiveSet* primitives = nullptr;
  std::vector<std::array<double, 2>> polygon;  // empty: point robot
  double cost_penalty = 1.0, nominal_speed = 0.4, time_to_turn_45 = 0.6;
};

/// The model of graph's map, primitives, footprint polygon and cost parameters.
ValidatorModel modelFor(const LatticeGraph& graph);

/// Does the closed square [i - e, i + 1 + e] x [j - e, j + 1 + e] meet segment p-q (cell units)?
bool segmentMeetsSquare(double px, double py, double qx, double qy, int i, int j, double e);
/// Does the closed polygon (cell units) meet the closed square [i, i + 1] x [j, j + 1] grown by e?
bool polygonMeetsSquare(const std::vector<std::array<double, 2>>& poly, int i, int j, double e);

/// The worst cost of the cells the segment (cell units) meets, or -1 if one is inscribed,
/// lethal, unknown or outside the map (`why` says which).
int centreSegmentWorst(const GridMap& map, double ax, double ay, double bx, double by,
                       std::string* why);
/// Is the footprint (metres, base frame) clear of lethal/unknown cells and inside the map at
/// every pose from a to b (metres relative to the point (ox, oy) in cell units)?
bool footprintMotionFree(const GridMap& map, const std::vector<std::array<double, 2>>& polygon,
                         double ox, double oy, const Pose2D& a, const Pose2D& b, std::string* why);
/// The documented edge cost for a motion of this length (m), turn (rad), multiplier and worst cell.
Cost documentedCost(const ValidatorModel& m, double length, double turn, double multiplier,
                    int worst);

/// Cost of primitive `p` from state `from`, or -1 if it is not collision-free. `why` explains.
Cost bruteForceEdgeCost(const ValidatorModel& m, const LatticeState& from, const MotionPrimitive& p,
                        std::string* why);

/// "" if the smoothed path is collision-free (every step by the brute force above), each piece
/// costs what it says (shortcut pieces by the documented formula and no longer than
/// max_piece_length; kept pieces are their primitive's poses from a state, at its cost) and the
/// pieces cover the poses and add up to path.cost; else what is wrong.
std::string validateSmoothedPath(const ValidatorModel& m, const SmoothedPath& path,
                                 double max_piece_length);

/// "" if the path is valid and costs `claimed_cost`, else what is wrong.
std::string validatePath(const ValidatorModel& m, const std::vector<LatticeState>& path,
                         Cost claimed_cost);

}  // namespace test
}  // namespace lattice
}  // namespace amha
