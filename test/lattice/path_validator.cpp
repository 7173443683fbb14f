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
      if (p[k] < 0.0)
        t0 = std::max(t0, r);
      else
        t1 = std::min(t1, r);
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
    if (segmentMeetsSquare(a[0], a[1], b[0], b[1], i, j, e))
      return true;  // an edge crosses or lies in it
  }
  return insidePolygon(poly, i + 0.5, j + 0.5);  // the square lies inside the polygon
}

namespace {

int costAt(const GridMap& map, int x, int y) {
  if (x < 0 || y < 0 || x >= map.width || y >= map.height) return 256;  // outside the map
  return map.cost[static_cast<std::size_t>(y) * map.width + x];
}

}  // namespace

int centreSegmentWorst(const GridMap& map, double ax, double ay, double bx, double by,
                       std::string* why) {
  // Every cell of a box around the segment, tested against it.
  int worst = 0;
  for (int j = static_cast<int>(std::floor(std::min(ay, by))) - 1;
       j <= static_cast<int>(std::floor(std::max(ay, by))) + 1; ++j) {
    for (int i = static_cast<int>(std::floor(std::min(ax, bx))) - 1;
         i <= static_cast<int>(std::floor(std::max(ax, bx))) + 1; ++i) {
      if (!segmentMeetsSquare(ax, ay, bx, by, i, j, 1e-6)) continue;
      const int c = costAt(map, i, j);
      if (c >= kInscribedCost) {
        if (why != nullptr)
          *why = "centre crosses cell (" + std::to_string(i) + ", " + std::to_string(j) +
                 ") of cost " + std::to_string(c);
        return -1;
      }
      worst = std::max(worst, c);
    }
  }
  return worst;
}

bool footprintMotionFree(const GridMap& map, const std::vector<std::array<double, 2>>& polygon,
                         double ox, double oy, const Pose2D& a, const Pose2D& b, std::string* why) {
  if (polygon.empty()) return true;
  const double res = map.resolution;
  double reach = 0.0;
  for (const auto& v : polygon) reach = std::max(reach, std::hypot(v[0], v[1]));
  std::vector<std::array<double, 2>> poly(polygon.size());
  // Poses so dense that no vertex moves more than 1/20 cell between two of them.
  const double dth = std::remainder(b.theta - a.theta, 2.0 * M_PI);
  const double move = std::hypot(b.x - a.x, b.y - a.y) + reach * std::fabs(dth);
  const int steps = std::max(1, static_cast<int>(std::ceil(move / (0.05 * res))));
  for (int s = 0; s <= steps; ++s) {
    const double t = static_cast<double>(s) / steps;
    const double x = a.x + t * (b.x - a.x), y = a.y + t * (b.y - a.y), th = a.theta + t * dth;
    const double c = std::cos(th), sn = std::sin(th);
    double minx = 1e18, maxx = -1e18, miny = 1e18, maxy = -1e18;
    for (std::size_t v = 0; v < polygon.size(); ++v) {
      const double vx = x + c * polygon[v][0] - sn * polygon[v][1];
      const double vy = y + sn * polygon[v][0] + c * polygon[v][1];
      poly[v] = {ox + vx / res, oy + vy / res};
      minx = std::min(minx, poly[v][0]);
      maxx = std::max(maxx, poly[v][0]);
      miny = std::min(miny, poly[v][1]);
      maxy = std::max(maxy, poly[v][1]);
    }
    for (int j = static_cast<int>(std::floor(miny)) - 1;
         j <= static_cast<int>(std::floor(maxy)) + 1; ++j) {
      for (int i = static_cast<int>(std::floor(minx)) - 1;
           i <= static_cast<int>(std::floor(maxx)) + 1; ++i) {
        if (costAt(map, i, j) < kLethalCost) continue;
        if (polygonMeetsSquare(poly, i, j, 0.0)) {
          if (why != nullptr)
            *why = "footprint touches cell (" + std::to_string(i) + ", " + std::to_string(j) + ")";
          return false;
        }
      }
    }
  }
  return true;
}

Cost documentedCost(const ValidatorModel& m, double length, double turn, double multiplier,
                    int worst) {
  const double turn_distance =
      m.time_to_turn_45 > 0.0 ? m.nominal_speed * turn * m.time_to_turn_45 / (M_PI / 4.0) : 0.0;
  const double units = std::ceil(1000.0 * std::max(length, turn_distance) - 1e-6);
  const long long base = std::max(1LL, std::llround(units * multiplier));
  const long long q = static_cast<long long>(
      std::ceil(65536.0 * m.cost_penalty * std::min(worst, 252) / 252.0 - 1e-9));
  return base + (base * q + 65535) / 65536;
}

Cost bruteForceEdgeCost(const ValidatorModel& m, const LatticeState& from, const MotionPrimitive& p,
                        std::string* why) {
  const GridMap& map = *m.map;
  const double res = map.resolution;
  auto fail = [&](const std::string& w) {
    if (why != nullptr) *why = w;
    return Cost(-1);
  };
  const double ox = from.x + 0.5, oy = from.y + 0.5;  // the start cell's centre, in cells
  int worst = 0;
  std::string w;
  for (std::size_t k = 0; k < p.poses.size(); ++k) {
    const Pose2D& a = p.poses[k];
    const Pose2D& b = p.poses[std::min(k + 1, p.poses.size() - 1)];
    const int c =
        centreSegmentWorst(map, ox + a.x / res, oy + a.y / res, ox + b.x / res, oy + b.y / res, &w);
    if (c < 0) return fail(w);
    worst = std::max(worst, c);
  }
  for (std::size_t k = 0; k + 1 < std::max<std::size_t>(p.poses.size(), 2); ++k) {
    const Pose2D& a = p.poses[k];
    const Pose2D& b = p.poses[std::min(k + 1, p.poses.size() - 1)];
    if (!footprintMotionFree(map, m.polygon, ox, oy, a, b, &w)) return fail(w);
  }
  // The documented cost.
  const PrimitiveSet& set = *m.primitives;
  double length = 0.0;
  for (std::size_t k = 1; k < p.poses.size(); ++k)
    length += std::hypot(p.poses[k].x - p.poses[k - 1].x, p.poses[k].y - p.poses[k - 1].y);
  double turn = std::fabs(std::remainder(
      set.heading_angles[p.end_heading] - set.heading_angles[p.start_heading], 2.0 * M_PI));
  return documentedCost(m, length, turn, p.cost_multiplier, worst);
}

ValidatorModel modelFor(const LatticeGraph& graph) {
  ValidatorModel m;
  m.map = &graph.map();
  m.primitives = &graph.primitives();
  m.polygon = graph.footprint().polygon;
  m.cost_penalty = graph.config().cost.penalty;
  m.nominal_speed = graph.config().cost.nominal_speed;
  m.time_to_turn_45 = graph.config().cost.time_to_turn_45;
  return m;
}

std::string validatePath(const ValidatorModel& m, const std::vector<LatticeState>& path,
                         Cost claimed_cost) {
  if (path.empty()) return "empty path";
  Cost total = 0;
  for (std::size_t k = 1; k < path.size(); ++k) {
    const LatticeState& a = path[k - 1];
    const LatticeState& b = path[k];
    Cost best = -1;
    std::string why = "no primitive joins them";
    for (const MotionPrimitive& p : m.primitives->primitives) {
      if (p.start_heading != a.heading || p.end_heading != b.heading || a.x + p.end_dx != b.x ||
          a.y + p.end_dy != b.y)
        continue;
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
      s << "step " << k << " (" << a.x << "," << a.y << "," << a.heading << ") -> (" << b.x << ","
        << b.y << "," << b.heading << "): " << why;
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

namespace amha {
namespace lattice {
namespace test {

std::string validateSmoothedPath(const ValidatorModel& m, const SmoothedPath& path,
                                 double max_piece_length) {
  const GridMap& map = *m.map;
  const double res = map.resolution, co = std::cos(map.origin_yaw), so = std::sin(map.origin_yaw);
  auto fail = [](std::size_t k, const std::string& what) {
    return "pose " + std::to_string(k) + ": " + what;
  };
  if (path.poses.empty()) return "no poses";
  // Grid frame, metres from the map's corner.
  std::vector<Pose2D> g;
  for (const Pose2D& p : path.poses) {
    const double dx = p.x - map.origin_x, dy = p.y - map.origin_y;
    g.push_back({co * dx + so * dy, -so * dx + co * dy, p.theta - map.origin_yaw});
  }
  std::string why;
  std::vector<int> worst(g.size(), 0);  // of the step from pose k to k + 1
  for (std::size_t k = 0; k + 1 < g.size(); ++k) {
    worst[k] = centreSegmentWorst(map, g[k].x / res, g[k].y / res, g[k + 1].x / res,
                                  g[k + 1].y / res, &why);
    if (worst[k] < 0) return fail(k, why);
    if (!footprintMotionFree(map, m.polygon, 0.0, 0.0, g[k], g[k + 1], &why)) return fail(k, why);
  }
  if (g.size() == 1 &&
      (centreSegmentWorst(map, g[0].x / res, g[0].y / res, g[0].x / res, g[0].y / res, &why) < 0 ||
       !footprintMotionFree(map, m.polygon, 0.0, 0.0, g[0], g[0], &why))) {
    return fail(0, why);
  }
  Cost total = 0;
  std::size_t expected_first = 0;
  for (std::size_t i = 0; i < path.pieces.size(); ++i) {
    const SmoothedPiece& piece = path.pieces[i];
    const std::string name = "piece " + std::to_string(i);
    if (piece.first != expected_first || piece.last <= piece.first || piece.last >= g.size())
      return name + ": bad pose range";
    expected_first = piece.last;
    Cost cost = -1;
    if (piece.shortcut) {
      double length = 0.0, turn = 0.0;
      int w = 0;
      for (std::size_t k = piece.first; k < piece.last; ++k) {
        length += std::hypot(g[k + 1].x - g[k].x, g[k + 1].y - g[k].y);
        turn += std::fabs(std::remainder(g[k + 1].theta - g[k].theta, 2.0 * M_PI));
        w = std::max(w, worst[k]);
      }
      if (piece.last > piece.first + 1 && length > max_piece_length + 1e-9)
        return name + ": longer than a primitive";
      cost = documentedCost(m, length, turn, piece.multiplier, w);
    } else {
      // A kept motion: the primitive's poses from the state at its first pose.
      if (piece.primitive < 0 ||
          piece.primitive >= static_cast<int>(m.primitives->primitives.size()))
        return name + ": no primitive";
      const MotionPrimitive& p = m.primitives->primitives[piece.primitive];
      const LatticeState s{static_cast<int>(std::floor(g[piece.first].x / res)),
                           static_cast<int>(std::floor(g[piece.first].y / res)), p.start_heading};
      if (p.poses.size() != piece.last - piece.first + 1)
        return name + ": not its primitive's poses";
      for (std::size_t k = 1; k < p.poses.size(); ++k) {  // the first is the previous motion's last
        const Pose2D& q = g[piece.first + k];
        if (std::fabs(q.x - ((s.x + 0.5) * res + p.poses[k].x)) > 1e-6 ||
            std::fabs(q.y - ((s.y + 0.5) * res + p.poses[k].y)) > 1e-6 ||
            std::fabs(std::remainder(q.theta - p.poses[k].theta, 2.0 * M_PI)) > 1e-6) {
          return name + ": not its primitive's poses";
        }
      }
      cost = bruteForceEdgeCost(m, s, p, &why);
      if (cost < 0) return name + ": " + why;
    }
    if (cost != piece.cost)
      return name + ": recomputed cost " + std::to_string(cost) + " != reported " +
             std::to_string(piece.cost);
    total += cost;
  }
  if (!path.pieces.empty() && expected_first + 1 != g.size())
    return "the pieces do not cover the poses";
  if (total != path.cost)
    return "pieces cost " + std::to_string(total) + " != reported " + std::to_string(path.cost);
  return "";
}

}  // namespace test
}  // namespace lattice
}  // namespace amha
