// Motion primitives from robot parameters: lattice-aligned headings, straight moves along each
// heading's lattice vector, arcs of radius >= the minimum turning radius that end exactly on a
// cell centre with the neighbouring heading, optional backward moves and turns in place.
// Primitives are built for the headings of the first octant and mapped to the others by the
// lattice's symmetries (90-degree rotations and the x <-> y reflection), which keeps every end
// pose exact.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "amha_planner/lattice/motion_primitives.h"

namespace amha {
namespace lattice {

namespace {

struct Vec {
  int x, y;
};

[[noreturn]] void fail(const std::string& what) {
  throw LatticeError(LatticeError::Kind::kConfig, "primitive generator: " + what);
}

// The N lattice directions, counter-clockwise from (1, 0).
std::vector<Vec> headingVectors(int n) {
  const int m = n / 8;  // headings per octant
  for (int amax = m + 1; amax <= 64; ++amax) {
    std::vector<Vec> octant{{1, 0}};
    bool ok = true;
    for (int k = 1; k < m && ok; ++k) {
      const double target = M_PI / 4.0 * k / m;
      Vec best{0, 0};
      double best_err = 1e9;
      for (int a = 1; a <= amax; ++a) {
        for (int b = 1; b < a; ++b) {
          if (std::gcd(a, b) != 1) continue;
          const double err = std::fabs(std::atan2(b, a) - target);
          if (err < best_err - 1e-12) {
            best_err = err;
            best = {a, b};
          }
        }
      }
      const Vec prev = octant.back();
      if (best.x == 0 || std::atan2(best.y, best.x) <= std::atan2(prev.y, prev.x)) ok = false;
      octant.push_back(best);
    }
    if (!ok) continue;
    std::vector<Vec> quadrant = octant;
    quadrant.push_back({1, 1});
    for (int k = m - 1; k >= 1; --k) quadrant.push_back({octant[k].y, octant[k].x});
    std::vector<Vec> all;
    for (int q = 0; q < 4; ++q) {
      for (Vec v : quadrant) {
        for (int r = 0; r < q; ++r) v = {-v.y, v.x};
        all.push_back(v);
      }
    }
    return all;
  }
  fail("cannot choose lattice directions for " + std::to_string(n) + " headings");
}

// A planar path: straight and circular pieces, sampled into poses.
struct Piece {
  double length;  // metres
  double curvature;  // signed, 1/m (0: straight)
};

std::vector<Pose2D> samplePath(double theta0, const std::vector<Piece>& pieces, double spacing,
                               double pose_offset) {
  double total = 0.0;
  for (const Piece& p : pieces) total += p.length;
  const int count = std::max(3, static_cast<int>(std::ceil(total / spacing)) + 1);
  std::vector<Pose2D> poses;
  for (int i = 0; i < count; ++i) {
    double s = total * i / (count - 1);
    double x = 0.0, y = 0.0, th = theta0;
    for (const Piece& p : pieces) {
      const double l = std::min(s, p.length);
      if (p.curvature == 0.0) {
        x += l * std::cos(th);
        y += l * std::sin(th);
      } else {
        const double r = 1.0 / p.curvature;
        const double th1 = th + l * p.curvature;
        x += r * (std::sin(th1) - std::sin(th));
        y += r * (std::cos(th) - std::cos(th1));
        th = th1;
      }
      s -= l;
      if (s <= 0.0) break;
    }
    poses.push_back({x, y, th + pose_offset});
  }
  return poses;
}

struct ArcSolution {
  bool found = false;
  Vec end{0, 0};
  std::vector<Piece> pieces;
  double radius = 0.0;
};

// The shortest path "straight then arc" or "arc then straight" from heading psi0 at the origin
// to a cell centre with heading psi1, with arc radius >= rmin. psi are travel directions.
ArcSolution solveArc(double psi0, double psi1, double rmin, double res) {
  const double delta = std::remainder(psi1 - psi0, 2.0 * M_PI);
  const double s = delta > 0 ? 1.0 : -1.0;
  const double ax = s * (std::sin(psi1) - std::sin(psi0)), ay = s * (std::cos(psi0) - std::cos(psi1));
  const double u0x = std::cos(psi0), u0y = std::sin(psi0), u1x = std::cos(psi1), u1y = std::sin(psi1);
  const int window = static_cast<int>(std::ceil(3.0 * rmin / res)) + 8;
  ArcSolution best;
  double best_len = 1e18, best_l = 1e18;
  for (int x = -window; x <= window; ++x) {
    for (int y = -window; y <= window; ++y) {
      if (x == 0 && y == 0) continue;
      const double px = x * res, py = y * res;
      for (int shape = 0; shape < 2; ++shape) {
        // shape 0: p = l u0 + r a (straight first); shape 1: p = r a + l u1 (arc first).
        const double ux = shape == 0 ? u0x : u1x, uy = shape == 0 ? u0y : u1y;
        const double det = ux * ay - uy * ax;
        if (std::fabs(det) < 1e-12) continue;
        const double l = (px * ay - py * ax) / det;
        const double r = (ux * py - uy * px) / det;
        if (l < -1e-9 || r < rmin - 1e-9) continue;
        const double len = std::max(0.0, l) + r * std::fabs(delta);
        if (len < best_len - 1e-9 || (len < best_len + 1e-9 && l < best_l)) {
          best_len = len;
          best_l = l;
          best.found = true;
          best.end = {x, y};
          best.radius = r;
          const Piece straight{std::max(0.0, l), 0.0}, arc{r * std::fabs(delta), s / r};
          best.pieces = shape == 0 ? std::vector<Piece>{straight, arc} : std::vector<Piece>{arc, straight};
        }
      }
    }
  }
  return best;
}

// Lattice symmetry: rotate by quarter * 90 degrees after an optional x <-> y reflection.
struct Symmetry {
  bool reflect;
  int quarter;
  Vec apply(Vec v) const {
    if (reflect) std::swap(v.x, v.y);
    for (int r = 0; r < quarter; ++r) v = {-v.y, v.x};
    return v;
  }
  Pose2D apply(const Pose2D& p) const {
    double x = p.x, y = p.y, th = p.theta;
    if (reflect) {
      std::swap(x, y);
      th = M_PI / 2.0 - th;
    }
    for (int r = 0; r < quarter; ++r) {
      const double nx = -y;
      y = x;
      x = nx;
    }
    return {x, y, th + quarter * M_PI / 2.0};
  }
};

}  // namespace

PrimitiveSet generatePrimitives(const PrimitiveGeneratorOptions& o) {
  if (!(o.resolution > 0.0) || !std::isfinite(o.resolution)) fail("resolution must be positive");
  if (o.num_headings < 8 || o.num_headings % 8 != 0 || o.num_headings > 256) {
    fail("the number of headings must be a multiple of 8 in 8..256, not " + std::to_string(o.num_headings));
  }
  if (!(o.turning_radius > 0.0) || !std::isfinite(o.turning_radius)) fail("the turning radius must be positive");
  if (o.turning_radius / o.resolution > 2000.0) fail("the turning radius is more than 2000 cells");
  if (!(o.reverse_multiplier > 0) || !(o.turn_in_place_multiplier > 0) || !(o.arc_multiplier > 0)) {
    fail("cost multipliers must be positive");
  }
  const int n = o.num_headings, m = n / 8;
  const std::vector<Vec> dirs = headingVectors(n);
  PrimitiveSet set;
  set.resolution = o.resolution;
  set.num_headings = n;
  set.uniform = (n == 8);
  set.min_turning_radius = o.turning_radius;
  for (const Vec& v : dirs) set.heading_angles.push_back(normalizeAngle(std::atan2(v.y, v.x)));
  auto indexOf = [&](Vec v) {
    const int g = std::gcd(std::abs(v.x), std::abs(v.y));
    v = {v.x / g, v.y / g};
    for (int i = 0; i < n; ++i) {
      if (dirs[i].x == v.x && dirs[i].y == v.y) return i;
    }
    fail("internal: direction not on the lattice");
  };
  const double res = o.resolution, spacing = 0.5 * res;
  const double long_len = o.long_straight_length > 0.0 ? o.long_straight_length : 8.0 * res;

  // Primitives of the base headings 0..m (0 to 45 degrees).
  std::vector<std::vector<MotionPrimitive>> base(m + 1);
  for (int h = 0; h <= m; ++h) {
    const Vec v = dirs[h];
    const double phi = set.heading_angles[h];
    const double vlen = std::hypot(v.x, v.y) * res;
    std::vector<MotionPrimitive>& out = base[h];
    auto straight = [&](int k, double mult, bool backward) {
      MotionPrimitive p;
      p.end_dx = (backward ? -k : k) * v.x;
      p.end_dy = (backward ? -k : k) * v.y;
      p.end_heading = h;
      p.cost_multiplier = mult;
      p.poses = samplePath(backward ? phi + M_PI : phi, {{k * vlen, 0.0}}, spacing, backward ? -M_PI : 0.0);
      out.push_back(std::move(p));
    };
    straight(1, 1.0, false);
    straight(std::max(2, static_cast<int>(std::lround(long_len / vlen))), 1.0, false);
    for (int backward = 0; backward <= (o.allow_reverse ? 1 : 0); ++backward) {
      if (backward) straight(1, o.reverse_multiplier, true);
      for (int side : {+1, -1}) {
        const int h1 = (h + side + n) % n;
        const double phi1 = set.heading_angles[h1];
        const double offset = backward ? M_PI : 0.0;  // travel direction vs heading
        const ArcSolution a = solveArc(phi + offset, phi1 + offset, o.turning_radius, res);
        if (!a.found) fail("no arc from heading " + std::to_string(h) + " to " + std::to_string(h1));
        MotionPrimitive p;
        p.end_dx = a.end.x;
        p.end_dy = a.end.y;
        p.end_heading = h1;
        p.cost_multiplier = backward ? o.reverse_multiplier * o.arc_multiplier : o.arc_multiplier;
        p.turning_radius = side * a.radius;  // signed as in SBPL's files: negative turns right
        p.poses = samplePath(phi + offset, a.pieces, spacing, -offset);
        out.push_back(std::move(p));
      }
    }
    if (o.turn_in_place) {
      for (int side : {+1, -1}) {
        const int h1 = (h + side + n) % n;
        const double d = std::remainder(set.heading_angles[h1] - phi, 2.0 * M_PI);
        MotionPrimitive p;
        p.end_heading = h1;
        p.cost_multiplier = o.turn_in_place_multiplier;
        for (int i = 0; i <= 4; ++i) p.poses.push_back({0.0, 0.0, phi + d * i / 4.0});
        out.push_back(std::move(p));
      }
    }
  }

  // Every heading from a base heading by a symmetry; pose angles are re-expressed near the
  // new heading and the ends snapped to the exact values.
  for (int h = 0; h < n; ++h) {
    const int quarter = h / (2 * m), r = h % (2 * m);
    const Symmetry g{r > m, quarter};
    const int b = r > m ? 2 * m - r : r;
    int id = 0;
    for (const MotionPrimitive& bp : base[b]) {
      MotionPrimitive p = bp;
      p.id = id++;
      p.start_heading = h;
      const Vec e = g.apply(Vec{bp.end_dx, bp.end_dy});
      p.end_dx = e.x;
      p.end_dy = e.y;
      p.end_heading = indexOf(g.apply(dirs[bp.end_heading]));
      if (g.reflect) p.turning_radius = -p.turning_radius;  // a mirror swaps left and right
      for (Pose2D& q : p.poses) q = g.apply(q);
      p.poses.front() = {0.0, 0.0, set.heading_angles[h]};
      p.poses.back() = {e.x * res, e.y * res, set.heading_angles[p.end_heading]};
      for (Pose2D& q : p.poses) q.theta = normalizeAngle(q.theta);
      set.primitives.push_back(std::move(p));
    }
  }
  return set;
}

}  // namespace lattice
}  // namespace amha
