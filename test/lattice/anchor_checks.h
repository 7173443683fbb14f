// A check the lattice heuristic tests share: a problem's anchor is consistent on every valid
// edge of the graph (gtest; header-only, so that non-gtest targets linking test_support.cpp
// stay free of it).
#pragma once

#include <gtest/gtest.h>

#include <utility>

#include "amha_planner/lattice/detail/lattice_problem.h"
#include "amha_planner/lattice/lattice_graph.h"

namespace amha {
namespace lattice {
namespace test {

/// h(p) <= cost(p, q) + h(q) for every valid edge p -> q, h = p.anchor (searching `backward`,
/// h measures from the start: h(q) <= cost + h(p)); edges whose bounded side is infinite are
/// skipped, and *edges counts the others.
inline ::testing::AssertionResult anchorConsistentOnEveryEdge(const LatticeGraph& g,
                                                              const LatticeProblem& p,
                                                              bool backward, int* edges) {
  *edges = 0;
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      for (int h = 0; h < g.numHeadings(); ++h) {
        if (!g.stateValid(x, y, h)) continue;
        for (const LatticeAction* a = g.actionsBegin(h); a != g.actionsEnd(h); ++a) {
          const Cost c = g.edgeCost(x, y, *a);
          if (c == kInvalidEdge) continue;
          HeuristicValue hp = p.anchor(x, y, h),
                         hq = p.anchor(x + a->dx, y + a->dy, a->end_heading);
          if (backward) std::swap(hp, hq);
          if (hq == kInfiniteHeuristic) continue;
          ++*edges;
          if (hp == kInfiniteHeuristic || static_cast<Cost>(hp) > c + static_cast<Cost>(hq)) {
            return ::testing::AssertionFailure()
                   << "edge (" << x << "," << y << "," << h << ") cost " << c << ": " << hp << " > "
                   << c << " + " << hq << (backward ? " backward" : "");
          }
        }
      }
    }
  }
  return ::testing::AssertionSuccess();
}

}  // namespace test
}  // namespace lattice
}  // namespace amha
