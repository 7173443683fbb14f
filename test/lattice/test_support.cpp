#include "test_support.h"

#include <sys/stat.h>
#include <unistd.h>
#include <cstdlib>
#include <queue>
#include <random>
#include <tuple>

namespace amha {
namespace lattice {
namespace test {

std::string sharedData() {
  const char* env = std::getenv("AMHA_SHARED_DATA");
  std::string dir = env != nullptr ? env : "../shared/data";
  struct stat st;
  if (stat((dir + "/sbpl/pr2.mprim").c_str(), &st) != 0) return "";
  return dir;
}

std::string tempDir() {
  char tmpl[] = "/tmp/amha_lattice_test_XXXXXX";
  const char* d = mkdtemp(tmpl);
  return d != nullptr ? std::string(d) : std::string("/tmp");
}

std::shared_ptr<GridMap> freeMap(int width, int height, double resolution) {
  auto m = std::make_shared<GridMap>();
  m->width = width;
  m->height = height;
  m->resolution = resolution;
  m->cost.assign(static_cast<std::size_t>(width) * height, 0);
  return m;
}

std::shared_ptr<GridMap> randomMap(int width, int height, double resolution, unsigned seed,
                                   int obstacles, int cost_max) {
  auto m = freeMap(width, height, resolution);
  std::mt19937 rng(seed);
  if (cost_max > 0) {
    std::uniform_int_distribution<int> c(0, cost_max);
    for (auto& v : m->cost) v = static_cast<std::uint8_t>(c(rng));
  }
  std::uniform_int_distribution<int> rx(0, width - 1), ry(0, height - 1),
      rs(1, std::max(2, width / 6));
  for (int k = 0; k < obstacles; ++k) {
    const int x0 = rx(rng), y0 = ry(rng), w = rs(rng), h = rs(rng);
    for (int y = y0; y < std::min(height, y0 + h); ++y) {
      for (int x = x0; x < std::min(width, x0 + w); ++x)
        m->cost[static_cast<std::size_t>(y) * width + x] = kLethalCost;
    }
  }
  return m;
}

std::vector<Cost> dijkstraFrom(const LatticeGraph& g, const LatticeState& s,
                               const std::function<Cost(int, int, const LatticeAction&)>& edge) {
  const int w = g.width(), nh = g.numHeadings();
  auto index = [&](int x, int y, int h) { return (static_cast<std::size_t>(y) * w + x) * nh + h; };
  std::vector<Cost> d(static_cast<std::size_t>(w) * g.height() * nh, kInfiniteCost);
  using Item = std::pair<Cost, std::tuple<int, int, int>>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  d[index(s.x, s.y, s.heading)] = 0;
  q.push({0, {s.x, s.y, s.heading}});
  while (!q.empty()) {
    const auto [c, st] = q.top();
    q.pop();
    const auto [x, y, h] = st;
    if (c != d[index(x, y, h)]) continue;
    for (const LatticeAction* a = g.actionsBegin(h); a != g.actionsEnd(h); ++a) {
      const Cost e = edge(x, y, *a);
      if (e < 0) continue;
      const std::size_t i = index(x + a->dx, y + a->dy, a->end_heading);
      if (c + e < d[i]) {
        d[i] = c + e;
        q.push({d[i], {x + a->dx, y + a->dy, a->end_heading}});
      }
    }
  }
  return d;
}

LatticeConfig cubicleConfig(const std::string& data, SbplEnvironment* env) {
  *env = loadSbplEnvironment(data + "/sbpl/cubicle-25mm-inflated-env.cfg");
  LatticeConfig c;
  c.motion.mprim_file = data + "/sbpl/pr2.mprim";
  c.robot.footprint = rectangle(0.01, 0.01);
  useSbplCostModel(*env, c);
  return c;
}

LatticeConfig smallRobot(unsigned seed) {
  LatticeConfig c;
  c.motion.turning_radius = 0.2;
  c.robot.footprint = rectangle(0.09, 0.05);
  c.motion.allow_reverse = seed % 3 == 0;
  c.cost.penalty = seed % 2 ? 4.0 : 1.0;
  c.cost.time_to_turn_45 = 1.0;
  c.heuristics.grid_anchor = seed % 4 != 1;
  c.heuristics.coarse_anchor = seed % 4 != 2;
  c.heuristics.anchor_turn_term = seed % 5 == 0;
  return c;
}

std::vector<char> floodFill(const GridMap& m, int sx, int sy) {
  std::vector<char> in(m.cost.size(), 0);
  if (m.at(sx, sy) >= kInscribedCost) return in;
  std::queue<std::pair<int, int>> q;
  q.push({sx, sy});
  in[static_cast<std::size_t>(sy) * m.width + sx] = 1;
  while (!q.empty()) {
    const auto [x, y] = q.front();
    q.pop();
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if (nx < 0 || ny < 0 || nx >= m.width || ny >= m.height) continue;
        const std::size_t i = static_cast<std::size_t>(ny) * m.width + nx;
        if (in[i] || m.cost[i] >= kInscribedCost) continue;
        in[i] = 1;
        q.push({nx, ny});
      }
    }
  }
  return in;
}

std::vector<std::array<double, 2>> rectangle(double hl, double hw) {
  return {{-hl, -hw}, {hl, -hw}, {hl, hw}, {-hl, hw}};
}

}  // namespace test
}  // namespace lattice
}  // namespace amha
