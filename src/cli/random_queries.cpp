// Seeded random start/goal pairs (see random_queries.h).
#include "random_queries.h"

#include <cmath>
#include <memory>
#include <random>

#include <opencv2/imgproc.hpp>

#include "amha_planner/lattice/lattice_planner.h"

namespace amha {
namespace cli {

std::vector<Query> randomQueries(const lattice::LatticeGraph& g, int count, unsigned seed,
                                 double min_distance, bool solvable) {
  const lattice::GridMap& m = g.map();
  cv::Mat free(m.height, m.width, CV_8U);
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x)
      free.at<std::uint8_t>(y, x) = m.at(x, y) < lattice::kInscribedCost ? 255 : 0;
  cv::Mat labels;
  cv::connectedComponents(free, labels, 8, CV_32S);
  std::unique_ptr<lattice::LatticePlanner> checker;
  if (solvable) {
    lattice::LatticeConfig c = g.config();
    c.heuristics.grid_anchor = true;
    c.heuristics.coarse_anchor = true;
    checker.reset(new lattice::LatticePlanner(std::make_shared<lattice::GridMap>(g.map()), c));
  }
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> rx(0, m.width - 1), ry(0, m.height - 1),
      rh(0, g.numHeadings() - 1);
  std::vector<Query> out;
  for (int tries = 0; static_cast<int>(out.size()) < count && tries < 1000000; ++tries) {
    const int sx = rx(rng), sy = ry(rng), sh = rh(rng), gx = rx(rng), gy = ry(rng), gh = rh(rng);
    if (!g.stateValid(sx, sy, sh) || !g.stateValid(gx, gy, gh)) continue;
    if (labels.at<int>(sy, sx) != labels.at<int>(gy, gx)) continue;
    if (std::hypot(gx - sx, gy - sy) * m.resolution < min_distance) continue;
    const Query q{g.stateToPose(sx, sy, sh), g.stateToPose(gx, gy, gh)};
    if (checker) {
      PlannerConfig w = defaultConfig(Algorithm::kWeightedAStar);
      SearchLimits limits;
      limits.time_limit_s = 2.0;
      if (checker->plan(q.start, q.goal, w, limits).solutions.empty()) continue;
    }
    out.push_back(q);
  }
  return out;
}

}  // namespace cli
}  // namespace amha
