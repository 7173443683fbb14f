// The legacy generator (PrimitiveGenerator::kLegacy, kept so that old benchmarks can be re-run;
// near_minimal_generator.cpp is the default): lattice-aligned headings, straight moves along each
// heading's lattice vector, arcs of radius >= the minimum turning radius that end exactly on a
// cell centre with the neighbouring heading, optional backward moves and turns in place.
// Primitives are built for the headings of the first octant and mapped to the others by the
// lattice's symmetries (90-degree rotations and the x <-> y reflection), which keeps every end
// pose exact.
#include <algorithm>
#include <cmath>

#include "amha_planner/lattice/motion_primitives.h"
#include "primitive_geometry.h"

namespace amha {
namespace lattice {

namespace {

using detail::headingVectors;
using detail::Piece;
using detail::samplePath;
using detail::Symmetry;
using detail::Vec;

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
  const double ax = s * (std::sin(psi1) - std::sin(psi0)),
               ay = s * (std::cos(psi0) - std::cos(psi1));
  const double u0x = std::cos(psi0), u0y = std::sin(psi0), u1x = std::cos(psi1),
               u1y = std::sin(psi1);
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
          best.pieces =
              shape == 0 ? std::vector<Piece>{straight, arc} : std::vector<Piece>{arc, straight};
        }
      }
    }
  }
  return best;
}

}  // namespace

PrimitiveSet generateLegacyPrimitives(const PrimitiveGeneratorOptions& o) {
  detail::validateGeneratorOptions(o);
  if (o.motion_model == MotionModel::kOmni)
    detail::generatorError("the legacy generator has no omnidirectional model");
  if (o.turning_radius / o.resolution > 2000.0)
    detail::generatorError("the turning radius is more than 2000 cells");
  if (!(o.arc_multiplier > 0)) detail::generatorError("cost multipliers must be positive");
  const int n = o.num_headings, m = n / 8;
  const std::vector<Vec> dirs = headingVectors(n);
  PrimitiveSet set = detail::latticeSet(o, dirs);
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
      p.poses = samplePath(backward ? phi + M_PI : phi, {{k * vlen, 0.0}}, spacing,
                           backward ? -M_PI : 0.0);
      p.straight_length = k * vlen;
      p.reverse = backward;
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
        if (!a.found)
          detail::generatorError("no arc from heading " + std::to_string(h) + " to " +
                                 std::to_string(h1));
        MotionPrimitive p;
        p.end_dx = a.end.x;
        p.end_dy = a.end.y;
        p.end_heading = h1;
        p.cost_multiplier = backward ? o.reverse_multiplier * o.arc_multiplier : o.arc_multiplier;
        p.turning_radius = side * a.radius;  // signed as in SBPL's files: negative turns right
        p.poses = samplePath(phi + offset, a.pieces, spacing, -offset);
        p.arc_length = a.pieces[0].curvature != 0.0 ? a.pieces[0].length : a.pieces[1].length;
        p.straight_length = a.pieces[0].curvature != 0.0 ? a.pieces[1].length : a.pieces[0].length;
        p.reverse = backward;
        out.push_back(std::move(p));
      }
    }
    if (o.turn_in_place && o.motion_model != MotionModel::kAckermann) {
      for (int side : {+1, -1})
        out.push_back(detail::turnOnTheSpot(set, h, side, o.turn_in_place_multiplier));
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
      set.primitives.push_back(detail::transformed(bp, g, h, dirs, set));
      set.primitives.back().id = id++;
    }
  }
  return set;
}

}  // namespace lattice
}  // namespace amha
