// Seeded random start/goal pairs on a lattice, shared by `amha bench lattice` and
// `amha bench queries`.
#pragma once

#include <vector>

#include "amha_planner/lattice/lattice_graph.h"

namespace amha {
namespace cli {

struct Query {
  lattice::Pose2D start, goal;
};

/// Seeded random queries: valid start and goal states (lattice states, as poses at cell
/// centres) in one 8-connected region of the cells the robot's centre may occupy (below the
/// inscribed cost), at least `min_distance` metres apart. With `solvable`, a pair is kept only
/// if weighted A* (w = 5, default anchor) finds a path within 2 s. Fewer than `count` if a
/// million draws do not find them. The same graph and seed give the same queries.
std::vector<Query> randomQueries(const lattice::LatticeGraph& g, int count, unsigned seed,
                                 double min_distance, bool solvable = false);

}  // namespace cli
}  // namespace amha
