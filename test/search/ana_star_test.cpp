// ANA* as van den Berg, Shah, Huang and Goldberg (AAAI 2011) define it, on hand-made graphs whose
// expansion order follows from the paper's pseudo-code (issue 22, item 8):
//  - while G = infinity every e(s) = (G - g(s)) / h(s) is infinite; the order is its limit as
//    G grows: smallest h first, then smallest g (greedy best-first search);
//  - ImproveSolution re-inserts a successor whenever its g drops and g + h < G, expanded or not
//    (there is no CLOSED list), so a state reached first by a costly route is expanded again
//    once a cheaper one is found: the re-expansions that cost ANA* millions of expansions
//    before its first solution on maps where A* needs a hundred thousand (docs/search.md).
#include <gtest/gtest.h>

#include <vector>

#include "test_graphs.h"

namespace amha {
namespace {

// Records every successors() call: one per expansion, and one per state of each reported path
// (the search recomputes its cost from the domain's edges).
struct RecordingGraph : testing::ExplicitGraph {
  std::vector<StateId> expanded;
  void successors(StateId s, std::vector<Edge>& out) override {
    expanded.push_back(s);
    ExplicitGraph::successors(s, out);
  }
};

RecordingGraph graph(std::vector<std::vector<Edge>> adj, std::vector<HeuristicValue> h,
                     StateId goal) {
  RecordingGraph g;
  g.adj = std::move(adj);
  for (HeuristicValue v : h) g.h.push_back({v});
  g.s_start = 0;
  g.s_goal = goal;
  return g;
}

SearchResult runAna(RecordingGraph& g) {
  return makePlanner(defaultConfig(Algorithm::kAnaStar))->search(g, SearchLimits());
}

// S = 0, goal G = 1, A = 2, B = 3, C = 4. S -> A (1), S -> B (10), A -> B (1), B -> C (1),
// C -> G (20); h = 4, 0, 3, 2, 1 (admissible and consistent). Greedy on h, ANA* first goes
// S, B, C and finds G = 31; then, with e(A) = 30 / 3 the best, A lowers g(B) from 10 to 2, and
// B and C are expanded again (e = 14.5, 28): the optimum 23.
TEST(AnaStar, ExpandsAsThePaperWithReexpansionsAfterAGDrop) {
  enum : StateId { S = 0, G = 1, A = 2, B = 3, C = 4 };
  RecordingGraph g =
      graph({{{A, 1}, {B, 10}}, {}, {{B, 1}}, {{C, 1}}, {{G, 20}}}, {4, 0, 3, 2, 1}, G);
  const SearchResult r = runAna(g);
  ASSERT_EQ(r.solutions.size(), 2u);
  EXPECT_EQ(r.solutions[0].cost, 31);
  EXPECT_EQ(r.solutions[1].cost, 23);
  EXPECT_EQ(r.status, SearchStatus::kProvenOptimal);
  EXPECT_EQ(r.solutions[0].expansions, 3u);
  EXPECT_EQ(r.expansions, 6u) << "B and C twice";
  // Expansions S, B, C; the report re-reads the first solution's edges (S, B, C); expansions
  // A, B, C; the second solution's edges (S, A, B, C).
  EXPECT_EQ(g.expanded, (std::vector<StateId>{S, B, C, S, B, C, A, B, C, S, A, B, C}));
  EXPECT_DOUBLE_EQ(r.solutions[1].nominal_bound, 10.0)
      << "E: the least e(s) expanded, e(A) = (31 - 1) / 3";
}

// When G is infinite, ties in h go to the smaller g: S -> X (3), S -> Y (1), both h = 2;
// X -> G (2), Y -> G (5). Y comes first, so the first solution is 6 (through Y), not 5.
TEST(AnaStar, BeforeTheFirstSolutionTiesInHGoToTheSmallerG) {
  enum : StateId { S = 0, G = 1, X = 2, Y = 3 };
  RecordingGraph g = graph({{{X, 3}, {Y, 1}}, {}, {{G, 2}}, {{G, 5}}}, {3, 0, 2, 2}, G);
  const SearchResult r = runAna(g);
  ASSERT_FALSE(r.solutions.empty());
  EXPECT_EQ(r.solutions.front().cost, 6);
  EXPECT_EQ(r.best().cost, 5);
  ASSERT_GE(g.expanded.size(), 2u);
  EXPECT_EQ(g.expanded[0], S);
  EXPECT_EQ(g.expanded[1], Y);
}

}  // namespace
}  // namespace amha
