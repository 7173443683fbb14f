// Polygon rasterisation, footprints and the cells swept along primitives.
#include "amha_planner/lattice/detail/footprint.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

namespace amha {
namespace lattice {

void rasterizeSegment(CellPoint p, CellPoint q, std::vector<CellOffset>& out) {
  const double e = kRasterEpsilon;
  const double minx = std::min(p.x, q.x), maxx = std::max(p.x, q.x);
  const int i0 = static_cast<int>(std::ceil(minx - 1.0 - e)),
            i1 = static_cast<int>(std::floor(maxx + e));
  const double dx = q.x - p.x;
  for (int i = i0; i <= i1; ++i) {
    double ylo, yhi;
    if (std::fabs(dx) < 1e-12) {
      ylo = std::min(p.y, q.y);
      yhi = std::max(p.y, q.y);
    } else {
      // Part of the segment inside the column [i - e, i + 1 + e].
      double t0 = (i - e - p.x) / dx, t1 = (i + 1 + e - p.x) / dx;
      if (t0 > t1) std::swap(t0, t1);
      t0 = std::max(t0, 0.0);
      t1 = std::min(t1, 1.0);
      if (t0 > t1) continue;
      const double ya = p.y + t0 * (q.y - p.y), yb = p.y + t1 * (q.y - p.y);
      ylo = std::min(ya, yb);
      yhi = std::max(ya, yb);
    }
    const int j0 = static_cast<int>(std::ceil(ylo - 1.0 - e)),
              j1 = static_cast<int>(std::floor(yhi + e));
    for (int j = j0; j <= j1; ++j) out.push_back({i, j});
  }
}

void rasterizePolygon(const CellPoint* poly, std::size_t n, std::vector<CellOffset>& out) {
  if (n == 0) return;
  double miny = poly[0].y, maxy = poly[0].y;
  for (std::size_t k = 0; k < n; ++k) {
    rasterizeSegment(poly[k], poly[(k + 1) % n], out);
    miny = std::min(miny, poly[k].y);
    maxy = std::max(maxy, poly[k].y);
  }
  if (n < 3) return;
  // Interior: cells whose centre is inside (even-odd), row by row. A row crosses at most n
  // edges: small polygons (footprints, swept quadrilaterals) need no allocation.
  std::array<double, 32> small;
  std::vector<double> large(n > small.size() ? n : 0);
  double* xs = n > small.size() ? large.data() : small.data();
  for (int j = static_cast<int>(std::floor(miny)); j <= static_cast<int>(std::floor(maxy)); ++j) {
    const double y = j + 0.5;
    std::size_t count = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const CellPoint a = poly[k], b = poly[(k + 1) % n];
      if ((a.y <= y) != (b.y <= y)) xs[count++] = a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y);
    }
    std::sort(xs, xs + count);
    for (std::size_t k = 0; k + 1 < count; k += 2) {
      const int i0 = static_cast<int>(std::ceil(xs[k] - 0.5)),
                i1 = static_cast<int>(std::floor(xs[k + 1] - 0.5));
      for (int i = i0; i <= i1; ++i) out.push_back({i, j});
    }
  }
}

void rasterizePolygon(const std::vector<CellPoint>& poly, std::vector<CellOffset>& out) {
  rasterizePolygon(poly.data(), poly.size(), out);
}

void uniqueCells(std::vector<CellOffset>& cells) {
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
}

namespace {

[[noreturn]] void robotError(const std::string& what) {
  throw LatticeError(LatticeError::Kind::kRobot, "robot footprint: " + what);
}

bool segmentsCross(const std::array<double, 2>& a, const std::array<double, 2>& b,
                   const std::array<double, 2>& c, const std::array<double, 2>& d) {
  auto orient = [](const std::array<double, 2>& p, const std::array<double, 2>& q,
                   const std::array<double, 2>& r) {
    const double v = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
    return (v > 1e-12) - (v < -1e-12);
  };
  const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  return o1 * o2 < 0 && o3 * o4 < 0;
}

double pointSegmentDistance(double px, double py, const std::array<double, 2>& a,
                            const std::array<double, 2>& b) {
  const double vx = b[0] - a[0], vy = b[1] - a[1];
  const double len2 = vx * vx + vy * vy;
  double t = len2 > 0 ? ((px - a[0]) * vx + (py - a[1]) * vy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(a[0] + t * vx - px, a[1] + t * vy - py);
}

bool containsOrigin(const std::vector<std::array<double, 2>>& poly) {
  bool inside = false;
  for (std::size_t k = 0, n = poly.size(); k < n; ++k) {
    const auto& a = poly[k];
    const auto& b = poly[(k + 1) % n];
    if ((a[1] <= 0.0) != (b[1] <= 0.0) && a[0] + (0.0 - a[1]) * (b[0] - a[0]) / (b[1] - a[1]) > 0.0)
      inside = !inside;
  }
  return inside;
}

}  // namespace

void RobotFootprint::checkFitsMap(int width, int height, double resolution) const {
  if (2.0 * inscribed_radius <= std::min(width, height) * resolution) return;
  std::ostringstream m;
  m << "its inscribed circle (radius " << inscribed_radius << " m) is wider than the map ("
    << width * resolution << " x " << height * resolution << " m): no pose on it is collision-free";
  robotError(m.str());
}

RobotFootprint RobotFootprint::fromConfig(const LatticeConfig& config) {
  RobotFootprint f;
  if (config.robot.footprint.empty()) {
    const double r = config.robot.radius;
    if (!std::isfinite(r) || r < 0.0) {
      std::ostringstream m;
      m << "radius " << r << " is not a non-negative number";
      robotError(m.str());
    }
    if (r == 0.0) return f;  // a point robot
    const int sides = 16;
    const double rv =
        r / std::cos(M_PI / sides);  // vertices outside so the 16-gon contains the circle
    for (int k = 0; k < sides; ++k) {
      const double a = 2.0 * M_PI * (k + 0.5) / sides;
      f.polygon.push_back({rv * std::cos(a), rv * std::sin(a)});
    }
    f.inscribed_radius = r;
    f.circumscribed_radius = rv;
    return f;
  }
  f.polygon = config.robot.footprint;
  const auto& p = f.polygon;
  const std::size_t n = p.size();
  if (n < 3) robotError("a polygon needs at least 3 points, got " + std::to_string(n));
  double area2 = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isfinite(p[k][0]) || !std::isfinite(p[k][1]))
      robotError("point " + std::to_string(k + 1) + " is not finite");
    if (std::hypot(p[k][0], p[k][1]) > 100.0)
      robotError("point " + std::to_string(k + 1) + " is more than 100 m from the origin");
    const auto& q = p[(k + 1) % n];
    area2 += p[k][0] * q[1] - q[0] * p[k][1];
  }
  if (std::fabs(area2) < 1e-12) robotError("the polygon has zero area");
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = a + 1; b < n; ++b) {
      if (b == a + 1 || (a == 0 && b == n - 1)) continue;  // neighbouring edges share a vertex
      if (segmentsCross(p[a], p[(a + 1) % n], p[b], p[(b + 1) % n])) {
        robotError("edges " + std::to_string(a + 1) + " and " + std::to_string(b + 1) +
                   " cross (self-intersecting polygon)");
      }
    }
  }
  double inscribed = 1e18;
  for (std::size_t k = 0; k < n; ++k) {
    inscribed = std::min(inscribed, pointSegmentDistance(0.0, 0.0, p[k], p[(k + 1) % n]));
    f.circumscribed_radius = std::max(f.circumscribed_radius, std::hypot(p[k][0], p[k][1]));
  }
  f.inscribed_radius = containsOrigin(p) ? inscribed : 0.0;
  return f;
}

std::vector<std::array<double, 2>> RobotFootprint::at(const Pose2D& pose) const {
  std::vector<std::array<double, 2>> out;
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);
  for (const auto& v : polygon)
    out.push_back({pose.x + c * v[0] - s * v[1], pose.y + s * v[0] + c * v[1]});
  return out;
}

void footprintInCells(const RobotFootprint& f, const Pose2D& pose, double res,
                      std::vector<CellPoint>& out) {
  footprintInCells(f, pose, res, out, std::cos(pose.theta), std::sin(pose.theta));
}

void footprintInCells(const RobotFootprint& f, const Pose2D& pose, double res,
                      std::vector<CellPoint>& out, double c, double s) {
  out.resize(f.polygon.size());
  for (std::size_t k = 0; k < f.polygon.size(); ++k) {
    const auto& v = f.polygon[k];
    out[k] = {(pose.x + c * v[0] - s * v[1]) / res + 0.5,
              (pose.y + s * v[0] + c * v[1]) / res + 0.5};
  }
}

int sweepSteps(const RobotFootprint& f, const Pose2D& a, const Pose2D& b, double res) {
  const double dth = std::remainder(b.theta - a.theta, 2.0 * M_PI);
  const double move = std::hypot(b.x - a.x, b.y - a.y) + f.circumscribed_radius * std::fabs(dth);
  return std::max(1, static_cast<int>(std::ceil(move / (0.25 * res))));
}

Pose2D sweepSample(const Pose2D& a, const Pose2D& b, int s, int n) {
  const double dth = std::remainder(b.theta - a.theta, 2.0 * M_PI);
  const double t = static_cast<double>(s) / n;
  return {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.theta + t * dth};
}

void rasterizeEdgeSweep(const std::vector<CellPoint>& from, const std::vector<CellPoint>& to,
                        std::size_t e, std::vector<CellOffset>& out) {
  // The region an edge sweeps between two placements (exact for a translation).
  const std::size_t n = from.size();
  const CellPoint quad[4] = {from[e], from[(e + 1) % n], to[(e + 1) % n], to[e]};
  rasterizePolygon(quad, 4, out);
}

void rasterizeEdgeSweep(const std::vector<CellPoint>& from, const std::vector<CellPoint>& to,
                        std::vector<CellOffset>& out) {
  for (std::size_t e = 0; e < from.size(); ++e) rasterizeEdgeSweep(from, to, e, out);
}

std::vector<CellOffset> footprintCells(const RobotFootprint& f, const Pose2D& pose, double res) {
  std::vector<CellOffset> cells;
  const CellPoint c{pose.x / res + 0.5, pose.y / res + 0.5};
  rasterizeSegment(c, c, cells);
  std::vector<CellPoint> poly;
  footprintInCells(f, pose, res, poly);
  rasterizePolygon(poly, cells);
  uniqueCells(cells);
  return cells;
}

PrimitiveCells primitiveCells(const RobotFootprint& f, const std::vector<Pose2D>& poses,
                              double res) {
  PrimitiveCells out;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const Pose2D& a = poses[k];
    const Pose2D& b = k + 1 < poses.size() ? poses[k + 1] : poses[k];
    rasterizeSegment({a.x / res + 0.5, a.y / res + 0.5}, {b.x / res + 0.5, b.y / res + 0.5},
                     out.centre);
  }
  uniqueCells(out.centre);
  if (f.polygon.empty() || poses.empty()) return out;

  std::vector<CellOffset>& cells = out.swept;
  std::vector<CellPoint> prev, cur;
  footprintInCells(f, poses.front(), res, prev);
  rasterizePolygon(prev, cells);
  std::size_t compacted = 0;
  for (std::size_t k = 1; k < poses.size(); ++k) {
    const int steps = sweepSteps(f, poses[k - 1], poses[k], res);
    for (int s = 1; s <= steps; ++s) {
      footprintInCells(f, sweepSample(poses[k - 1], poses[k], s, steps), res, cur);
      rasterizeEdgeSweep(prev, cur, cells);
      if (cells.size() > 2 * compacted + 4096) {
        uniqueCells(cells);
        compacted = cells.size();
      }
      std::swap(prev, cur);
    }
  }
  uniqueCells(cells);
  return out;
}

}  // namespace lattice
}  // namespace amha
