// Seeded random start/goal pairs for the lattice benchmarks (`amha bench lattice`, `amha bench
// smooth`).
#pragma once

#include <vector>

#include "amha_planner/lattice/lattice_graph.h"

namespace amha {
namespace cli {

struct Query {
  lattice::Pose2D start, goal;
};

/// Valid start and goal states in one connected region of the cells the robot's centre may
/// occupy, at least `min_distance` metres apart. With `solvable` (the benchmark runs), a pair is
/// kept only if weighted A* (w = 5, default anchor) finds a path within 2 s, so every pair
/// measures anytime behaviour rather than a proof of unreachability.
std::vector<Query> randomQueries(const lattice::LatticeGraph& g, int count, unsigned seed, double min_distance,
                                 bool solvable = false);

}  // namespace cli
}  // namespace amha
