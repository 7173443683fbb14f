// Small explicit search problems for testing the algorithms against an exact solver.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "amha_planner/search/planner.h"

namespace amha {
namespace testing {

/// An explicit graph with a table of heuristic values (column 0 is the anchor).
class ExplicitGraph : public SearchProblem {
 public:
  std::vector<std::vector<Edge>> adj;
  std::vector<std::vector<HeuristicValue>> h;  // h[state][i]
  StateId s_start = 0, s_goal = 0;
  std::size_t n_heuristics = 1;
  std::uint64_t successor_calls = 0;
  bool small_keys = false;  // let the search use bucket queues (costs and h are integers)

  StateId start() const override { return s_start; }
  StateId goal() const override { return s_goal; }
  void successors(StateId s, std::vector<Edge>& out) override {
    ++successor_calls;
    out.assign(adj[s].begin(), adj[s].end());
  }
  std::size_t numHeuristics() const override { return n_heuristics; }
  void heuristics(StateId s, HeuristicValue* out, std::size_t count) override {
    for (std::size_t i = 0; i < count; ++i) out[i] = h[s][i];
  }
  bool smallIntegerKeys() const override { return small_keys; }
  std::size_t size() const { return adj.size(); }

  /// Inflation bases b[state][i] (SearchProblem::hasInflationBases), if not empty.
  std::vector<std::vector<HeuristicValue>> b;
  bool hasInflationBases() const override { return !b.empty(); }
  void bases(StateId s, HeuristicValue* out, std::size_t count) override {
    for (std::size_t i = 0; i < count; ++i) out[i] = b[s][i];
  }
};

/// Exact cost-to-goal of every state (Dijkstra on reversed edges); kInfiniteCost if unreachable.
std::vector<Cost> distancesToGoal(const ExplicitGraph& g);

/// Kinds of inadmissible heuristics the generators attach.
enum class BadHeuristic {
  kOverestimate,  // 10x the true distance
  kNoise,         // true distance times a random factor in [0, 4]
  kRandom,        // unrelated random values
  kSomeInfinite,  // true distance, but infinite on a random quarter of the states
  kMisleading,    // large near the goal, small far from it
};

struct GenOptions {
  std::uint32_t seed = 1;
  double anchor_scale = 1.0;       // anchor = floor(scale * true distance): consistent
  std::size_t n_inadmissible = 4;  // cycles through the BadHeuristic kinds
};

/// Random W x H 8-connected grid with obstacles and random cell costs (1..9); start top-left
/// region, goal bottom-right region (both free).
ExplicitGraph randomGrid(int width, int height, double obstacle_prob, const GenOptions& opt);

/// Random directed graph with n states, about `degree` out-edges each, weights 1..100.
ExplicitGraph randomGraph(int n, int degree, const GenOptions& opt);

/// For seeds 1..10: a width x height randomGrid and a randomGraph of n states, each with 3
/// inadmissible heuristics and the anchor scaled by odd_scale (odd seeds) or even_scale; the
/// grids of every third seed allow bucket queues when `buckets`.
std::vector<ExplicitGraph> gridsAndGraphs(int width, int height, int n, double odd_scale,
                                          double even_scale, bool buckets);

/// Checks a solution: path from start to goal along edges, cost equals the sum of the cheapest
/// edges used, bounds ordered 1 <= certified <= nominal, cost <= certified * optimal.
/// Returns "" when valid, else a description of the problem.
std::string validateSolution(ExplicitGraph& g, const Solution& s, Cost optimal);

/// A problem on an unbounded 4-connected grid whose ids are assigned on discovery; the goal is
/// walled off, so a search explores until a limit stops it.
class EndlessGrid : public SearchProblem {
 public:
  explicit EndlessGrid(std::size_t n_heuristics = 1);
  StateId start() const override { return 0; }
  StateId goal() const override { return 1; }
  void successors(StateId s, std::vector<Edge>& out) override;
  std::size_t numHeuristics() const override { return n_heuristics_; }
  void heuristics(StateId s, HeuristicValue* out, std::size_t count) override;
  std::size_t memoryBytes() const override { return cells_.size() * 16 * 3; }

 private:
  StateId idOf(std::int64_t x, std::int64_t y);
  std::size_t n_heuristics_;
  std::unordered_map<std::int64_t, StateId> ids_;
  std::vector<std::pair<std::int64_t, std::int64_t>> cells_;
};

}  // namespace testing
}  // namespace amha
