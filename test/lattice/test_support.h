// Helpers for the lattice tests: shared data paths, temp dirs, small random maps.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "amha_planner/lattice/detail/lattice_problem.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/lattice/map_loaders.h"

namespace amha {
namespace lattice {
namespace test {

/// ../shared/data from AMHA_SHARED_DATA, or "" if absent (tests then GTEST_SKIP).
std::string sharedData();
/// A fresh empty directory under /tmp.
std::string tempDir();
/// A width x height map at `resolution`, every cell free (cost 0).
std::shared_ptr<GridMap> freeMap(int width, int height, double resolution);
/// A width x height map at `resolution` with random rectangular obstacles (lethal) and random
/// cell costs in 0..cost_max elsewhere; a border of free cells is left around (x0, y0) spots.
std::shared_ptr<GridMap> randomMap(int width, int height, double resolution, unsigned seed,
                                   int obstacles, int cost_max);
/// The cheapest cost from s to every state, indexed (y * width + x) * headings + heading, by a
/// Dijkstra over the graph's actions; edge(x, y, a) is the cost of a from (x, y), or < 0 for
/// none (kInfiniteCost where unreachable).
std::vector<Cost> dijkstraFrom(const LatticeGraph& g, const LatticeState& s,
                               const std::function<Cost(int, int, const LatticeAction&)>& edge);

/// A robot 0.18 m x 0.10 m turning on 0.2 m, its reverse motions, cost penalty and anchor
/// options varied with `seed` (for the random maps of randomMap at 0.05 m).
LatticeConfig smallRobot(unsigned seed);

/// The start cell's 8-connected component of cells below kInscribedCost (1 = in it), by a
/// plain flood fill; all 0 if the start cell itself is not below it.
std::vector<char> floodFill(const GridMap& m, int sx, int sy);
/// SBPL's inflated cubicle at 25 mm (*env receives it) with the PR2's primitives, a footprint of
/// a few millimetres (the map is inflated already) and SBPL's cost model.
LatticeConfig cubicleConfig(const std::string& data, SbplEnvironment* env);
/// A small rectangular footprint (half length, half width in metres).
std::vector<std::array<double, 2>> rectangle(double half_length, double half_width);

}  // namespace test
}  // namespace lattice
}  // namespace amha

#define AMHA_REQUIRE_SHARED_DATA(var)                          \
  const std::string var = ::amha::lattice::test::sharedData(); \
  if (var.empty()) GTEST_SKIP() << "shared data (AMHA_SHARED_DATA) absent"
