// An independent check of lattice paths: it shares no geometry code with the planner. For each
// step it looks for a primitive of the file/generator joining the two states, rasterises the
// robot's centre path and footprint by brute force (every cell of a bounding box tested
// against the segment/polygon, the footprint at very densely interpolated poses), checks the
// cells, and recomputes the documented edge cost.
#pragma once

#include <string>
#include <vector>

#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/lattice/lattice_problem.h"
#include "amha_planner/lattice/motion_primitives.h"

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

/// Cost of primitive `p` from state `from`, or -1 if it is not collision-free. `why` explains.
Cost bruteForceEdgeCost(const ValidatorModel& m, const LatticeState& from, const MotionPrimitive& p, std::string* why);

/// "" if the path is valid and costs `claimed_cost`, else what is wrong.
std::string validatePath(const ValidatorModel& m, const std::vector<LatticeState>& path, Cost claimed_cost);

}  // namespace test
}  // namespace lattice
}  // namespace amha
