#include "path_validator.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace amha {
namespace lattice {
namespace test {

bool segmentMeetsSquare(double px, double py, double qx, double qy, int i, int j, double e) {
  // Liang-Barsky clipping of p + t (q - p), t in [0, 1], against the grown square.
  double t0 = 0.0, t1 = 1.0;
  const double dx = qx - px, dy = qy - py;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {px - (i - e), (i + 1 + e) - px, py - (j - e), (j + 1 + e) - py};
  for (int k = 0; k < 4; ++k) {
    if (p[k] == 0.0) {
      if (q[k] < 0.0) return false;
    } else {
      const double r = q[k] / p[k];
      if (p[k] < 0.0) t0 = std::max(t0, r); else t1 = std::min(t1, r);
      if (t0 > t1) return false;
    }
  }
  return true;
}

namespace {
bool insidePolygon(const std::vector<std::array<double, 2>>& poly, double x, double y) {
  bool in = false;
  for (std::size_t k = 0, n = poly.size(); k < n; ++k) {
    const auto& a = poly[k];
    const auto& b = poly[(k + 1) % n];
    if ((a[1] > y) != (b[1] > y) && x < a[0] + (y - a[1]) * (b[0] - a[0]) / (b[1] - a[1])) in = !in;
  }
  return in;
}
}  // namespace

bool polygonMeetsSquare(const std::vector<std::array<double, 2>>& poly, int i, int j, double e) {
  for (std::size_t k = 0, n = poly.size(); k < n; ++k) {
    const auto& a = poly[k];
    const auto& b = poly[(k + 1) % n];
    if (segmentMeetsSquare(a[0], a[1], b[0], b[1], i, j, e)) return true;  // an edge crosses or lies in it
  }
  return insidePolygon(poly, i + 0.5, j + 0.5);  // the square lies inside the polygon
}

Cost bruteForceEdgeCost(const ValidatorModel& m, const LatticeState& from, const MotionPrimitive& p, std::string* why) {
  const GridMap& map = *m.map;
  const double res = map.resolution;
  auto cost_at = [&](int x, int y) -> int {
    if (x < 0 || y < 0 || x >= map.width || y >= map.height) return 256;  // outside the map
    return map.cost[static_cast<std::size_t>(y) * map.width + x];
  };
  auto fail = [&](const std::string& w) {
    if (why != nullptr) *why = w;
    return Cost(-1);
  };
  // Centre cells: every cell of a box around each segment, tested against the segment.
  int worst = 0;
  for (std::size_t k = 0; k < p.poses.size(); ++k) {
    const Pose2D& a = p.poses[k];
    const Pose2D& b = p.poses[std::min(k + 1, p.poses.size() - 1)];
    const double ax = from.x + a.x / res + 0.5, ay = from.y + a.y / res + 0.5;
    const double bx = from.x + b.x / res + 0.5, by = from.y + b.y / res + 0.5;
    for (int j = static_cast<int>(std::floor(std::min(ay, by))) - 1; j <= static_cast<int>(std::floor(std::max(ay, by))) + 1; ++j) {
      for (int i = static_cast<int>(std::floor(std::min(ax, bx))) - 1; i <= static_cast<int>(std::floor(std::max(ax, bx))) + 1; ++i) {
        if (!segmentMeetsSquare(ax, ay, bx, by, i, j, 1e-6)) continue;
        const int c = cost_at(i, j);
        if (c >= kInscribedCost) return fail("centre crosses cell (" + std::to_string(i) + ", " + std::to_string(j) + ") of cost " + std::to_string(c));
        worst = std::max(worst, c);
      }
    }
  }
  // Footprint at poses so dense that no vertex moves more than 1/20 cell between two of them.
  if (!m.polygon.empty()) {
    double reach = 0.0;
    for (const auto& v : m.polygon) reach = std::max(reach, std::hypot(v[0], v[1]));
    std::vector<std::array<double, 2>> poly(m.polygon.size());
    for (std::size_t k = 0; k + 1 < std::max<std::size_t>(p.poses.size(), 2); ++k) {
      const Pose2D& a = p.poses[k];
      const Pose2D& b = p.poses[std::min(k + 1, p.poses.size() - 1)];
      const double dth = std::remainder(b.theta - a.theta, 2.0 * M_PI);
      const double move = std::hypot(b.x - a.x, b.y - a.y) + reach * std::fabs(dth);
      const int steps = std::max(1, static_cast<int>(std::ceil(move / (0.05 * res))));
      for (int s = 0; s <= steps; ++s) {
        const double t = static_cast<double>(s) / steps;
        const double x = a.x + t * (b.x - a.x), y = a.y + t * (b.y - a.y), th = a.theta + t * dth;
        const double c = std::cos(th), sn = std::sin(th);
        double minx = 1e18, maxx = -1e18, miny = 1e18, maxy = -1e18;
        for (std::size_t v = 0; v < m.polygon.size(); ++v) {
          const double vx = x + c * m.polygon[v][0] - sn * m.polygon[v][1];
          const double vy = y + sn * m.polygon[v][0] + c * m.polygon[v][1];
          poly[v] = {from.x + vx / res + 0.5, from.y + vy / res + 0.5};
          minx = std::min(minx, poly[v][0]);
          maxx = std::max(maxx, poly[v][0]);
          miny = std::min(miny, poly[v][1]);
          maxy = std::max(maxy, poly[v][1]);
        }
        for (int j = static_cast<int>(std::floor(miny)) - 1; j <= static_cast<int>(std::floor(maxy)) + 1; ++j) {
          for (int i = static_cast<int>(std::floor(minx)) - 1; i <= static_cast<int>(std::floor(maxx)) + 1; ++i) {
            if (cost_at(i, j) < kLethalCost) continue;
            if (polygonMeetsSquare(poly, i, j, 0.0)) {
              return fail("footprint touches cell (" + std::to_string(i) + ", " + std::to_string(j) + ")");
            }
          }
        }
      }
    }
  }
  // The documented cost.
  const PrimitiveSet& set = *m.primitives;
  double length = 0.0;
  for (std::size_t k = 1; k < p.poses.size(); ++k) length += std::hypot(p.poses[k].x - p.poses[k - 1].x, p.poses[k].y - p.poses[k - 1].y);
  double turn = std::fabs(std::remainder(set.heading_angles[p.end_heading] - set.heading_angles[p.start_heading], 2.0 * M_PI));
  const double turn_distance = m.time_to_turn_45 > 0.0 ? m.nominal_speed * turn * m.time_to_turn_45 / (M_PI / 4.0) : 0.0;
  const double units = std::ceil(1000.0 * std::max(length, turn_distance) - 1e-6);
  const long long base = std::max(1LL, std::llround(units * p.cost_multiplier));
  const long long q = static_cast<long long>(std::ceil(65536.0 * m.cost_penalty * std::min(worst, 252) / 252.0 - 1e-9));
  return base + (base * q + 65535) / 65536;
}

ValidatorModel modelFor(const LatticeGraph& graph) {
  ValidatorModel m;
  m.map = &graph.map();
  m.primitives = &graph.primitives();
  m.polygon = graph.footprint().polygon;
  m.cost_penalty = graph.config().cost_penalty;
  m.nominal_speed = graph.config().nominal_speed;
  m.time_to_turn_45 = graph.config().time_to_turn_45;
  return m;
}

std::string validatePath(const ValidatorModel& m, const std::vector<LatticeState>& path, Cost claimed_cost) {
  if (path.empty()) return "empty path";
  Cost total = 0;
  for (std::size_t k = 1; k < path.size(); ++k) {
    const LatticeState& a = path[k - 1];
    const LatticeState& b = path[k];
    Cost best = -1;
    std::string why = "no primitive joins them";
    for (const MotionPrimitive& p : m.primitives->primitives) {
      if (p.start_heading != a.heading || p.end_heading != b.heading || a.x + p.end_dx != b.x || a.y + p.end_dy != b.y) continue;
      std::string w;
      const Cost c = bruteForceEdgeCost(m, a, p, &w);
      if (c < 0) {
        why = w;
        continue;
      }
      if (best < 0 || c < best) best = c;
    }
    if (best < 0) {
      std::ostringstream s;
      s << "step " << k << " (" << a.x << "," << a.y << "," << a.heading << ") -> (" << b.x << "," << b.y << "," << b.heading << "): " << why;
      return s.str();
    }
    total += best;
  }
  if (total != claimed_cost) {
    std::ostringstream s;
    s << "recomputed cost " << total << " != reported " << claimed_cost;
    return s.str();
  }
  return "";
}

}  // namespace test
}  // namespace lattice
}  // namespace amha
