// A near-minimal control set (Pivtoraiko & Kelly 2005): of all the curves that join a lattice
// state of a first-octant heading to another lattice state, taken shortest first, keep those
// that the kept ones (and their symmetric images) cannot replace within a tolerance. Whether they
// can is a lookup: for every first-octant start, the shortest composition of kept primitives to
// every state near the origin is kept up to date as primitives are added (distances only fall,
// so each addition is a Dijkstra from the states it improves).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <queue>
#include <set>
#include <tuple>

#include "amha_planner/lattice/motion_primitives.h"
#include "primitive_geometry.h"

namespace amha {
namespace lattice {

namespace {

using detail::Piece;
using detail::Symmetry;
using detail::Vec;

// A candidate, small: many wait in the queue. Its shape is computed again if it is kept.
struct Candidate {
  double length = 0.0;     // metres
  int start = 0, end = 0;  // headings; start is a first-octant heading
  Vec cell{0, 0};

  bool operator>(const Candidate& o) const {
    return std::tie(length, start, end, cell.y, cell.x) >
           std::tie(o.length, o.start, o.end, o.cell.y, o.cell.x);
  }
};

struct Shape {
  std::vector<Piece> pieces;
  double radius = 0.0;  // signed: > 0 turns left; 0 straight
};

// The curve from (0, 0) at travel direction phi0 to (ex, ey) at phi1 made of a straight, an arc
// and a straight, one of the straights empty: the arc is tangent to both headings' lines, at
// equal distance from where they cross. Its length, or 0 if the lines cross behind the start
// or beyond the end, or the arc's radius would be below rmin.
double arcCurve(double phi0, double phi1, double ex, double ey, double rmin,
                Shape* shape = nullptr) {
  const double delta = std::remainder(phi1 - phi0, 2.0 * M_PI);
  const double sd = std::sin(delta);
  if (std::fabs(sd) < 1e-9) return 0.0;
  const double u0x = std::cos(phi0), u0y = std::sin(phi0), u1x = std::cos(phi1),
               u1y = std::sin(phi1);
  // t0 u0 + t1 u1 = e: the lines cross t0 along the start's heading, t1 before the end.
  const double t0 = (ex * u1y - ey * u1x) / sd, t1 = (u0x * ey - u0y * ex) / sd;
  if (t0 < -1e-9 || t1 < -1e-9) return 0.0;
  const double t = std::min(t0, t1), r = t / std::tan(0.5 * std::fabs(delta));
  if (!(r >= rmin * (1.0 - 1e-9))) return 0.0;
  const Piece arc{r * std::fabs(delta), (delta > 0.0 ? 1.0 : -1.0) / r};
  const double straight = std::fabs(t0 - t1);
  if (shape != nullptr) {
    shape->pieces.clear();
    if (t0 > t1 && straight > 1e-12) shape->pieces.push_back({straight, 0.0});
    shape->pieces.push_back(arc);
    if (t1 > t0 && straight > 1e-12) shape->pieces.push_back({straight, 0.0});
    shape->radius = delta > 0.0 ? r : -r;
  }
  return arc.length + straight;
}

// The 8 lattice symmetries.
std::vector<Symmetry> symmetries() {
  std::vector<Symmetry> out;
  for (int reflect = 0; reflect < 2; ++reflect)
    for (int quarter = 0; quarter < 4; ++quarter) out.push_back({reflect == 1, quarter});
  return out;
}

// A primitive of the set being built, as the distance tables see it.
struct Edge {
  int dx, dy, end;
  float length;
};

// Shortest compositions of the kept primitives from each first-octant start state to every
// state within `radius` cells of it. Only distances up to a bound, raised as longer candidates
// come up, are settled: the relaxations beyond it wait in the queue, so each source is one
// Dijkstra search paused at the bound (distances only fall as primitives are added; a state a
// new primitive improves is queued again).
class CompositionTable {
 public:
  CompositionTable(int headings, int sources, int radius)
      : n_(headings), r_(radius), side_(2 * radius + 1), edges_(headings), sources_(sources) {
    for (Source& s : sources_)
      s.dist.assign(static_cast<std::size_t>(side_) * side_ * headings, kInf);
    for (int s = 0; s < sources; ++s) {
      sources_[s].dist[index(0, 0, s)] = 0.0f;
      sources_[s].queue.emplace(0.0f, 0, 0, s);
    }
  }

  /// The shortest composition's length (m) from source's start state to (x, y, h), exact if it
  /// is at most the bound given to settle().
  float distance(int source, int x, int y, int h) const {
    return inside(x, y) ? sources_[source].dist[index(x, y, h)] : kInf;
  }

  /// Adds primitives (of any start heading): queues every state they shorten.
  void add(const std::vector<std::pair<int, Edge>>& added) {
    for (const auto& [start, e] : added) edges_[start].push_back(e);
    for (Source& s : sources_) {
      for (const auto& [start, e] : added) {
        for (int y = -r_; y <= r_; ++y) {
          for (int x = -r_; x <= r_; ++x) {
            const float g = s.dist[index(x, y, start)];
            if (g < kInf) relax(s, g, x + e.dx, y + e.dy, e);
          }
        }
      }
    }
  }

  /// Makes every distance up to `bound` exact.
  void settle(float bound) {
    for (Source& s : sources_) {
      while (!s.queue.empty() && std::get<0>(s.queue.top()) <= bound) {
        const auto [g, x, y, h] = s.queue.top();
        s.queue.pop();
        if (g > s.dist[index(x, y, h)]) continue;  // a shorter one came later
        for (const Edge& e : edges_[h]) relax(s, g, x + e.dx, y + e.dy, e);
      }
    }
  }

 private:
  using Entry = std::tuple<float, int, int, int>;
  struct Source {
    std::vector<float> dist;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  };
  static constexpr float kInf = std::numeric_limits<float>::infinity();

  bool inside(int x, int y) const { return x >= -r_ && x <= r_ && y >= -r_ && y <= r_; }
  std::size_t index(int x, int y, int h) const {
    return (static_cast<std::size_t>(y + r_) * side_ + static_cast<std::size_t>(x + r_)) * n_ + h;
  }
  void relax(Source& s, float g, int x, int y, const Edge& e) {
    if (!inside(x, y)) return;  // compositions leaving the table count as none: keeps more
    const float ng = g + e.length;
    float& cur = s.dist[index(x, y, e.end)];
    if (ng < cur) {
      cur = ng;
      s.queue.emplace(ng, x, y, e.end);
    }
  }

  int n_, r_, side_;
  std::vector<std::vector<Edge>> edges_;
  std::vector<Source> sources_;
};

}  // namespace

PrimitiveSet generateNearMinimalPrimitives(const PrimitiveGeneratorOptions& o) {
  detail::validateGeneratorOptions(o);
  if (!(o.tolerance >= 0.0 && o.tolerance <= 1.0))
    detail::generatorError("the tolerance must be in [0, 1]");
  if (o.end_tolerance < 0 || o.end_tolerance > 3)
    detail::generatorError("the end tolerance must be 0 .. 3 cells");
  const int n = o.num_headings, m = n / 8;
  const std::vector<Vec> dirs = detail::headingVectors(n);
  PrimitiveSet set = detail::latticeSet(o, dirs);
  const double res = o.resolution, rmin = o.turning_radius;
  // Candidates are at most this long: a quarter turn at the minimum radius with straights of a
  // radius on both sides, and a few cells more; in practice the search stops well before.
  const double max_length = (M_PI / 2.0 + 2.0) * rmin + 4.0 * res;
  const int reach = static_cast<int>(std::ceil(max_length / res));
  const int table_radius = static_cast<int>(std::ceil((1.0 + o.tolerance) * max_length / res)) + 1;
  const double table_size =
      static_cast<double>(m + 1) * n * (2.0 * table_radius + 1) * (2.0 * table_radius + 1);
  if (table_size > 3e7) {
    char what[160];
    std::snprintf(
        what, sizeof what,
        "a turning radius of %.1f cells with %d headings is too large for the near-minimal "
        "generator (use the legacy generator)",
        rmin / res, n);
    detail::generatorError(what);
  }
  const std::vector<Symmetry> group = symmetries();
  auto headingOf = [&](Vec v) { return detail::directionIndex(dirs, v); };

  // Candidates by length; those of Chebyshev radius `ring` are all at least ring cells long, so
  // after generating ring k every pending candidate shorter than k + 1 cells is final in order.
  std::priority_queue<Candidate, std::vector<Candidate>, std::greater<Candidate>> pending;
  auto generateRing = [&](int ring) {
    for (int y = -ring; y <= ring; ++y) {
      for (int x = -ring; x <= ring; ++x) {
        if (std::max(std::abs(x), std::abs(y)) != ring) continue;
        for (int h0 = 0; h0 <= m; ++h0) {
          const double phi0 = set.heading_angles[h0];
          Candidate c;
          c.start = h0;
          c.cell = {x, y};
          const Vec v = dirs[h0];
          if (x * v.y == y * v.x && x * v.x + y * v.y > 0) {  // a straight along the heading
            c.end = h0;
            c.length = std::hypot(x, y) * res;
            pending.push(c);
            continue;
          }
          for (int h1 = 0; h1 < n; ++h1) {
            const double delta = std::remainder(set.heading_angles[h1] - phi0, 2.0 * M_PI);
            if (h1 == h0 || std::fabs(delta) > M_PI / 2.0 + 1e-9) continue;
            c.end = h1;
            c.length = arcCurve(phi0, set.heading_angles[h1], x * res, y * res, rmin);
            if (c.length > 0.0 && c.length <= max_length) pending.push(c);
          }
        }
      }
    }
  };

  CompositionTable table(n, m + 1, table_radius);
  std::vector<std::pair<Candidate, Symmetry>> kept;  // every image of the kept candidates, once
  std::set<std::tuple<int, int, int, int>> images;   // (start, dx, dy, end) of the whole set
  const int quiet_rings = std::max(5, static_cast<int>(std::ceil(0.5 * rmin / res)));
  const int first_ring_that_counts = static_cast<int>(std::ceil(M_PI / 2.0 * rmin / res));
  int quiet = 0;
  for (int ring = 1; ring <= reach && quiet < quiet_rings; ++ring) {
    generateRing(ring);
    bool added = false;
    while (!pending.empty() && pending.top().length < (ring + 1) * res - 1e-12) {
      const Candidate c = pending.top();
      pending.pop();
      table.settle(static_cast<float>((1.0 + o.tolerance) * c.length + 1e-6));
      // Turns may be replaced by compositions that end next to them; straights only exactly
      // (the origin is next to the one-cell straight).
      const int near = c.end == c.start ? 0 : o.end_tolerance;
      double composed = std::numeric_limits<double>::infinity();
      for (int dy = -near; dy <= near; ++dy) {
        for (int dx = -near; dx <= near; ++dx) {
          composed = std::min<double>(composed,
                                      table.distance(c.start, c.cell.x + dx, c.cell.y + dy, c.end));
        }
      }
      if (composed <= (1.0 + o.tolerance) * c.length + 1e-6) continue;
      std::vector<std::pair<int, Edge>> edges;
      for (const Symmetry& g : group) {
        const int s = headingOf(g.apply(dirs[c.start])), e = headingOf(g.apply(dirs[c.end]));
        const Vec d = g.apply(c.cell);
        if (images.insert({s, d.x, d.y, e}).second) {
          edges.push_back({s, Edge{d.x, d.y, e, static_cast<float>(c.length)}});
          kept.push_back({c, g});
        }
      }
      table.add(edges);
      added = true;
    }
    quiet = added || ring < first_ring_that_counts ? 0 : quiet + 1;
  }

  // The kept candidates' images, with exact end poses.
  std::vector<MotionPrimitive> all;
  for (const auto& [c, g] : kept) {
    Shape shape;
    if (c.end == c.start) {
      shape.pieces = {{c.length, 0.0}};
    } else {
      arcCurve(set.heading_angles[c.start], set.heading_angles[c.end], c.cell.x * res,
               c.cell.y * res, rmin, &shape);
    }
    MotionPrimitive base;
    base.start_heading = c.start;
    base.end_heading = c.end;
    base.end_dx = c.cell.x;
    base.end_dy = c.cell.y;
    base.turning_radius = shape.radius;
    for (const Piece& p : shape.pieces)
      (p.curvature != 0.0 ? base.arc_length : base.straight_length) += p.length;
    base.poses = detail::samplePath(set.heading_angles[c.start], shape.pieces, 0.5 * res, 0.0);
    all.push_back(detail::transformed(base, g, headingOf(g.apply(dirs[c.start])), dirs, set));
  }
  if (o.turn_in_place && o.motion_model != MotionModel::kAckermann) {
    for (int h = 0; h < n; ++h) {
      for (int side : {+1, -1})
        all.push_back(detail::turnOnTheSpot(set, h, side, o.turn_in_place_multiplier));
    }
  }
  if (o.motion_model == MotionModel::kOmni) {
    // Sideways: the shortest straight of the heading a quarter turn away, keeping the heading.
    std::vector<MotionPrimitive> sideways;
    for (const MotionPrimitive& p : all) {
      if (p.turning_radius != 0.0 || p.end_heading != p.start_heading || p.poses.size() < 2)
        continue;
      const Vec v = dirs[p.start_heading];
      if (p.end_dx != v.x || p.end_dy != v.y) continue;  // only the one-vector straight
      for (int side : {+1, -1}) {
        MotionPrimitive q = p;
        q.start_heading = q.end_heading = ((p.start_heading - side * n / 4) % n + n) % n;
        for (Pose2D& pose : q.poses) pose.theta = set.heading_angles[q.start_heading];
        sideways.push_back(std::move(q));
      }
    }
    all.insert(all.end(), sideways.begin(), sideways.end());
  }
  std::stable_sort(all.begin(), all.end(), [](const MotionPrimitive& a, const MotionPrimitive& b) {
    return std::tie(a.start_heading, a.end_heading, a.end_dy, a.end_dx) <
           std::tie(b.start_heading, b.end_heading, b.end_dy, b.end_dx);
  });
  set.primitives = std::move(all);
  detail::numberByHeading(set);
  if (o.allow_reverse) addBackwardTwins(set, o.reverse_multiplier);
  return set;
}

}  // namespace lattice
}  // namespace amha
