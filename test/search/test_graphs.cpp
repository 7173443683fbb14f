#include "test_graphs.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <random>
#include <sstream>

namespace amha {
namespace testing {

std::vector<Cost> distancesToGoal(const ExplicitGraph& g) {
  std::vector<std::vector<Edge>> rev(g.size());
  for (StateId s = 0; s < g.size(); ++s) {
    for (const Edge& e : g.adj[s]) rev[e.to].push_back(Edge{s, e.cost});
  }
  std::vector<Cost> d(g.size(), kInfiniteCost);
  using Item = std::pair<Cost, StateId>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> pq;
  d[g.s_goal] = 0;
  pq.push({0, g.s_goal});
  while (!pq.empty()) {
    auto [c, s] = pq.top();
    pq.pop();
    if (c != d[s]) continue;
    for (const Edge& e : rev[s]) {
      if (c + e.cost < d[e.to]) {
        d[e.to] = c + e.cost;
        pq.push({d[e.to], e.to});
      }
    }
  }
  return d;
}

namespace {

HeuristicValue clampH(double v) {
  if (!(v < 4e9)) return kInfiniteHeuristic - 1;
  return static_cast<HeuristicValue>(std::max(0.0, v));
}

// Fills g.h from the exact distances: a consistent anchor and a mix of bad heuristics.
void attachHeuristics(ExplicitGraph& g, const GenOptions& opt, std::mt19937& rng) {
  g.n_heuristics = 1 + opt.n_inadmissible;
  const std::vector<Cost> d = distancesToGoal(g);
  Cost dmax = 1;
  for (Cost c : d) {
    if (c < kInfiniteCost) dmax = std::max(dmax, c);
  }
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  g.h.assign(g.size(), std::vector<HeuristicValue>(g.n_heuristics, 0));
  for (StateId s = 0; s < g.size(); ++s) {
    const bool reach = d[s] < kInfiniteCost;
    const double ds = reach ? static_cast<double>(d[s]) : 0.0;
    // floor(scale * d) is consistent for scale <= 1; unreachable states may get infinity.
    g.h[s][0] =
        reach ? static_cast<HeuristicValue>(std::floor(opt.anchor_scale * ds)) : kInfiniteHeuristic;
    for (std::size_t i = 1; i < g.n_heuristics; ++i) {
      HeuristicValue v = 0;
      switch (static_cast<BadHeuristic>((i - 1) % 5)) {
        case BadHeuristic::kOverestimate:
          v = clampH(10.0 * ds);
          break;
        case BadHeuristic::kNoise:
          v = clampH(ds * 4.0 * u01(rng));
          break;
        case BadHeuristic::kRandom:
          v = clampH(u01(rng) * 3.0 * static_cast<double>(dmax));
          break;
        case BadHeuristic::kSomeInfinite:
          v = (u01(rng) < 0.25 || !reach) ? kInfiniteHeuristic : clampH(ds);
          break;
        case BadHeuristic::kMisleading:
          v = clampH(static_cast<double>(dmax) - ds);
          break;
      }
      g.h[s][i] = v;
    }
  }
  g.h[g.s_goal][0] = 0;
}

}  // namespace

ExplicitGraph randomGrid(int width, int height, double obstacle_prob, const GenOptions& opt) {
  std::mt19937 rng(opt.seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::uniform_int_distribution<int> cost(1, 9);
  ExplicitGraph g;
  const int n = width * height;
  std::vector<char> blocked(n);
  std::vector<int> cell_cost(n);
  for (int i = 0; i < n; ++i) {
    blocked[i] = u01(rng) < obstacle_prob;
    cell_cost[i] = cost(rng);
  }
  g.s_start = 0;
  g.s_goal = static_cast<StateId>(n - 1);
  blocked[g.s_start] = blocked[g.s_goal] = 0;
  g.adj.assign(n, {});
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const int s = y * width + x;
      if (blocked[s]) continue;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          if (dx == 0 && dy == 0) continue;
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
          const int t = ny * width + nx;
          if (blocked[t]) continue;
          const Cost base = (dx != 0 && dy != 0) ? 14 : 10;  // octile, fixed point x10
          g.adj[s].push_back(Edge{static_cast<StateId>(t), base * cell_cost[t]});
        }
      }
    }
  }
  attachHeuristics(g, opt, rng);
  return g;
}

std::vector<ExplicitGraph> gridsAndGraphs(int width, int height, int n, double odd_scale,
                                          double even_scale, bool buckets) {
  std::vector<ExplicitGraph> out;
  for (std::uint32_t seed = 1; seed <= 10; ++seed) {
    GenOptions o;
    o.seed = seed;
    o.n_inadmissible = 3;
    o.anchor_scale = seed % 2 ? odd_scale : even_scale;
    out.push_back(randomGrid(width, height, 0.25, o));
    out.back().small_keys = buckets && seed % 3 == 0;
    out.push_back(randomGraph(n, 3, o));
  }
  return out;
}

ExplicitGraph randomGraph(int n, int degree, const GenOptions& opt) {
  std::mt19937 rng(opt.seed);
  std::uniform_int_distribution<int> node(0, n - 1);
  std::uniform_int_distribution<int> weight(1, 100);
  ExplicitGraph g;
  g.adj.assign(n, {});
  for (int s = 0; s < n; ++s) {
    for (int k = 0; k < degree; ++k) {
      const int t = node(rng);
      if (t != s) g.adj[s].push_back(Edge{static_cast<StateId>(t), weight(rng)});
    }
  }
  g.s_start = 0;
  g.s_goal = static_cast<StateId>(n - 1);
  attachHeuristics(g, opt, rng);
  return g;
}

std::string validateSolution(ExplicitGraph& g, const Solution& s, Cost optimal) {
  std::ostringstream err;
  if (s.path.empty()) return "empty path";
  if (s.path.front() != g.s_start) return "path does not start at the start";
  if (s.path.back() != g.s_goal) return "path does not end at the goal";
  Cost sum = 0;
  for (std::size_t k = 1; k < s.path.size(); ++k) {
    Cost best = kInfiniteCost;
    for (const Edge& e : g.adj[s.path[k - 1]]) {
      if (e.to == s.path[k]) best = std::min(best, e.cost);
    }
    if (best == kInfiniteCost) {
      err << "no edge " << s.path[k - 1] << " -> " << s.path[k];
      return err.str();
    }
    sum += best;
  }
  if (sum != s.cost) {
    err << "reported cost " << s.cost << " != sum of edges " << sum;
    return err.str();
  }
  if (!(s.certified_bound >= 1.0) || s.certified_bound > s.nominal_bound) {
    err << "bounds out of order: certified " << s.certified_bound << " nominal " << s.nominal_bound;
    return err.str();
  }
  if (static_cast<double>(s.cost) >
      s.certified_bound * static_cast<double>(optimal) * (1 + 1e-12)) {
    err << "cost " << s.cost << " > certified " << s.certified_bound << " * optimal " << optimal;
    return err.str();
  }
  return "";
}

EndlessGrid::EndlessGrid(std::size_t n_heuristics) : n_heuristics_(n_heuristics) {
  idOf(0, 0);              // start
  idOf(1000000, 1000000);  // goal: surrounded by nothing that leads to it
}

StateId EndlessGrid::idOf(std::int64_t x, std::int64_t y) {
  const std::int64_t key = static_cast<std::int64_t>((static_cast<std::uint64_t>(x) << 32) ^
                                                     (static_cast<std::uint64_t>(y) & 0xffffffffu));
  auto it = ids_.find(key);
  if (it != ids_.end()) return it->second;
  const StateId id = static_cast<StateId>(cells_.size());
  ids_.emplace(key, id);
  cells_.push_back({x, y});
  return id;
}

void EndlessGrid::successors(StateId s, std::vector<Edge>& out) {
  out.clear();
  if (s == 1) return;
  const auto [x, y] = cells_[s];
  static const int kDx[4] = {1, -1, 0, 0}, kDy[4] = {0, 0, 1, -1};
  for (int k = 0; k < 4; ++k) out.push_back(Edge{idOf(x + kDx[k], y + kDy[k]), 1});
}

void EndlessGrid::heuristics(StateId s, HeuristicValue* out, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) out[i] = (s == 1) ? 0 : static_cast<HeuristicValue>(i);
}

}  // namespace testing
}  // namespace amha
