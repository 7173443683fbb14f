// PathSmoother: lattice path -> motions -> driving stretches -> Dubins shortcuts between their
// states, each tested and costed as the lattice tests and costs a primitive.
#include "amha_planner/lattice/path_smoother.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "amha_planner/lattice/detail/dubins_path.h"
#include "amha_planner/lattice/detail/footprint.h"
#include "primitive_geometry.h"

namespace amha {
namespace lattice {

using detail::polylineLength;

MotionKind motionKind(const MotionPrimitive& p) {
  if (polylineLength(p.poses) < 1e-9) return MotionKind::kInPlace;
  bool forward = false, backward = false;
  for (std::size_t k = 1; k < p.poses.size(); ++k) {
    const Pose2D& a = p.poses[k - 1];
    const Pose2D& b = p.poses[k];
    const double dx = b.x - a.x, dy = b.y - a.y;
    if (std::hypot(dx, dy) < 1e-12) {
      if (std::fabs(std::remainder(b.theta - a.theta, 2.0 * M_PI)) > 1e-12)
        return MotionKind::kMixed;
      continue;
    }
    const double along_a = dx * std::cos(a.theta) + dy * std::sin(a.theta);
    const double along_b = dx * std::cos(b.theta) + dy * std::sin(b.theta);
    if (along_a > 0.0 && along_b > 0.0) {
      forward = true;
    } else if (along_a < 0.0 && along_b < 0.0) {
      backward = true;
    } else {
      return MotionKind::kMixed;  // sideways, or turning through the perpendicular
    }
  }
  if (forward == backward) return MotionKind::kMixed;
  return forward ? MotionKind::kForward : MotionKind::kBackward;
}

namespace {

/// 2 sin(|dtheta| / 2) / |dp|: the curvature of the circle through both positions that is
/// tangent to both headings when they are symmetric about the chord (exact for arc samples).
double stepCurvature(const Pose2D& a, const Pose2D& b) {
  const double chord = std::hypot(b.x - a.x, b.y - a.y);
  const double dth = std::fabs(std::remainder(b.theta - a.theta, 2.0 * M_PI));
  if (chord <= 0.0) return dth > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
  return 2.0 * std::sin(0.5 * dth) / chord;
}

double gridAngle(const GridMap& m, double theta) { return theta - m.origin_yaw; }

/// An angle difference in (-pi, pi], for differences within a few turns (quicker than
/// std::remainder, which the loops over every pose of every trial would feel).
double smallAngle(double d) {
  while (d > M_PI) d -= 2.0 * M_PI;
  while (d <= -M_PI) d += 2.0 * M_PI;
  return d;
}

}  // namespace

double modelTurningRadius(const LatticeGraph& graph) {
  double curvature = 0.0;
  for (const MotionPrimitive& p : graph.primitives().primitives) {
    const MotionKind m = motionKind(p);
    if (m != MotionKind::kForward && m != MotionKind::kBackward) continue;
    for (std::size_t k = 1; k < p.poses.size(); ++k)
      curvature = std::max(curvature, stepCurvature(p.poses[k - 1], p.poses[k]));
  }
  return curvature > 0.0 ? 1.0 / curvature : std::numeric_limits<double>::infinity();
}

double longestPrimitiveLength(const LatticeGraph& graph) {
  double longest = 0.0;
  for (const MotionPrimitive& p : graph.primitives().primitives)
    longest = std::max(longest, polylineLength(p.poses));
  return longest;
}

/// One motion of the input: graph action `action` from state (x, y, heading), the input's
/// poses [first, last].
struct PathSmoother::Edge {
  int action = -1;
  int x = 0, y = 0, heading = 0;
  std::size_t first = 0, last = 0;
  Cost cost = 0;
};

/// A shortcut: poses relative to its first state's cell centre (as a primitive's), its pieces
/// (indices into these poses) and cost.
struct PathSmoother::Candidate {
  std::vector<Pose2D> poses;
  std::vector<SmoothedPiece> pieces;
  Cost cost = 0;
  std::size_t to_edge = 0;  // the shortcut ends where this input edge ends
};

PathSmoother::PathSmoother(const LatticeGraph& graph, const SmootherOptions& options)
    : graph_(graph) {
  const double model = modelTurningRadius(graph);
  radius_ = options.turning_radius > 0.0 ? options.turning_radius : model;
  if (!std::isfinite(options.turning_radius) || options.turning_radius < 0.0 ||
      (options.turning_radius > 0.0 && options.turning_radius < model * (1.0 - 1e-9))) {
    std::ostringstream m;
    m << "smoothing turning radius " << options.turning_radius
      << " m: must be finite and at least the motion model's " << model << " m (0: the model's)";
    throw std::invalid_argument(m.str());
  }
  piece_length_ = std::max(longestPrimitiveLength(graph), graph.map().resolution);
  const LatticeConfig& c = graph.config();
  omega_ = c.cost.time_to_turn_45 > 0.0 ? (M_PI / 4.0) / c.cost.time_to_turn_45 : 0.0;
  const PrimitiveSet& set = graph.primitives();
  for (const LatticeAction& a : graph.actions()) {
    const MotionPrimitive& p = set.primitives[a.primitive];
    actions_.push_back(Action{motionKind(p), p.cost_multiplier});
  }
}

std::vector<PathSmoother::Edge> PathSmoother::parse(const std::vector<Pose2D>& poses,
                                                    std::vector<Pose2D>& g) const {
  const GridMap& m = graph_.map();
  const PrimitiveSet& set = graph_.primitives();
  const double res = m.resolution, co = std::cos(m.origin_yaw), so = std::sin(m.origin_yaw);
  const std::size_t n = poses.size();
  // The poses in the grid frame (metres from the map's corner, radians).
  g.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Pose2D& p = poses[k];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.theta)) {
      throw std::invalid_argument("lattice path: pose " + std::to_string(k) + " is not finite");
    }
    const double dx = p.x - m.origin_x, dy = p.y - m.origin_y;
    g[k] = {co * dx + so * dy, -so * dx + co * dy, gridAngle(m, p.theta)};
  }
  const double tol = 1e-4 * res, angle_tol = 1e-6;
  auto same = [&](const Pose2D& a, double x, double y, double theta) {
    return std::fabs(a.x - x) <= tol && std::fabs(a.y - y) <= tol &&
           std::fabs(smallAngle(a.theta - theta)) <= angle_tol;
  };
  // Cheapest explanation of poses [0, k] as valid motions (several may explain the same poses,
  // e.g. one long straight move or several short ones).
  const Cost inf = std::numeric_limits<Cost>::max();
  std::vector<Cost> best(n, inf);
  std::vector<Edge> via(n);
  best[0] = 0;
  bool collides = false;  // a motion explaining poses after the last one reached collides
  std::size_t reached = 0;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    if (best[k] == inf) continue;
    reached = k;
    collides = false;
    const int x = static_cast<int>(std::floor(g[k].x / res)),
              y = static_cast<int>(std::floor(g[k].y / res));
    if (x < 0 || y < 0 || x >= m.width || y >= m.height) continue;
    // The state a motion ended in: its last pose discretises to it (as the .mprim reader
    // checks), but need not be its exact centre (files round their poses).
    const int h = set.headingIndex(g[k].theta);
    const double cx = (x + 0.5) * res, cy = (y + 0.5) * res;
    for (const LatticeAction* a = graph_.actionsBegin(h); a != graph_.actionsEnd(h); ++a) {
      const std::vector<Pose2D>& pp = set.primitives[a->primitive].poses;
      const std::size_t last = k + pp.size() - 1;
      if (pp.size() < 2 || last >= n) continue;
      bool match = true;
      for (std::size_t i = pp.size() - 1; i >= 1 && match; --i) {  // the end first: it differs most
        match = same(g[k + i], cx + pp[i].x, cy + pp[i].y, pp[i].theta);
      }
      if (!match) continue;
      const Cost c = graph_.edgeCost(x, y, *a);
      if (c == kInvalidEdge) {
        collides = true;
        continue;
      }
      if (best[k] + c < best[last]) {
        best[last] = best[k] + c;
        via[last] = Edge{static_cast<int>(a - graph_.actions().data()), x, y, h, k, last, c};
      }
    }
  }
  if (best[n - 1] == inf) {
    throw std::invalid_argument(
        "not a path of this lattice: no valid motion of its primitives explains the poses after "
        "pose " +
        std::to_string(reached) +
        (collides ? " (the motion that matches them collides or leaves the map)" : ""));
  }
  std::vector<Edge> edges;
  for (std::size_t k = n - 1; k > 0; k = via[k].first) edges.push_back(via[k]);
  std::reverse(edges.begin(), edges.end());
  return edges;
}

bool PathSmoother::provablyFree(double cx, double cy, double reach) const {
  // The swept cells lie within the footprint's circumscribed radius of the positions, and their
  // centres within half a diagonal of that; the point's cell centre is half a diagonal away.
  const GridMap& m = graph_.map();
  const int x = static_cast<int>(std::floor(cx)), y = static_cast<int>(std::floor(cy));
  if (x < 0 || y < 0 || x >= m.width || y >= m.height) return false;
  const double needed = graph_.footprint().circumscribed_radius / m.resolution + reach + 1.4143;
  const std::vector<float>& radii = graph_.clearanceRadii();
  const std::size_t k = std::lower_bound(radii.begin(), radii.end(), needed) - radii.begin();
  const std::vector<std::uint8_t>& clearance = graph_.clearance();  // empty: nothing sweeps
  return k < radii.size() && !clearance.empty() &&
         clearance[static_cast<std::size_t>(y) * m.width + x] > k;
}

namespace {

/// The cells rasterizeSegment and rasterizePolygon may give for points within [minx, maxx] x
/// [miny, maxy] (cell units relative to cell (x0, y0)): their squares grown by kRasterEpsilon.
struct CellBox {
  int i0, i1, j0, j1;
  CellBox(double minx, double maxx, double miny, double maxy)
      : i0(static_cast<int>(std::ceil(minx - 1.0 - kRasterEpsilon))),
        i1(static_cast<int>(std::floor(maxx + kRasterEpsilon))),
        j0(static_cast<int>(std::ceil(miny - 1.0 - kRasterEpsilon))),
        j1(static_cast<int>(std::floor(maxy + kRasterEpsilon))) {}
  /// Around the points of a and b, grown by `grow` cells.
  template <class Points>
  static CellBox around(const Points& a, const Points& b, double grow = 0.0) {
    double minx = a[0].x, maxx = a[0].x, miny = a[0].y, maxy = a[0].y;
    for (const auto* set : {&a, &b}) {
      for (const CellPoint& p : *set) {
        minx = std::min(minx, p.x);
        maxx = std::max(maxx, p.x);
        miny = std::min(miny, p.y);
        maxy = std::max(maxy, p.y);
      }
    }
    return CellBox(minx - grow, maxx + grow, miny - grow, maxy + grow);
  }
};

/// Is a cell of the box (relative to cell (x0, y0)) lethal, unknown or outside the map?
inline bool boxBlocked(const GridMap& m, int x0, int y0, const CellBox& b) {
  if (x0 + b.i0 < 0 || y0 + b.j0 < 0 || x0 + b.i1 >= m.width || y0 + b.j1 >= m.height) return true;
  for (int j = b.j0; j <= b.j1; ++j) {
    const std::uint8_t* row = &m.cost[static_cast<std::size_t>(y0 + j) * m.width + x0];
    std::uint8_t worst = 0;  // a maximum without branches, which the compiler vectorises
    for (int i = b.i0; i <= b.i1; ++i) worst = std::max(worst, row[i]);
    if (worst >= kLethalCost) return true;
  }
  return false;
}

}  // namespace

struct PathSmoother::Scratch {
  std::vector<CellPoint> prev, cur;
  std::vector<CellOffset> cells;
  std::vector<double> along;      // path length from the first pose to each (metres)
  std::vector<std::size_t> near;  // footprint edges with a blocked cell near them in a step
};

bool PathSmoother::sweepFree(int x0, int y0, const std::vector<Pose2D>& poses, std::size_t first,
                             std::size_t last, Scratch& scratch) const {
  const GridMap& m = graph_.map();
  const double res = m.resolution;
  const RobotFootprint& f = graph_.footprint();
  // Proof by clearance for the whole range: every pose lies within `reach` (path length) of
  // the middle one. Cell units of the map: cell (x, y) is [x, x + 1] x [y, y + 1].
  const std::size_t mid = (first + last) / 2;
  const std::vector<double>& along = scratch.along;
  const double before = along[mid] - along[first], after = along[last] - along[mid];
  if (provablyFree(x0 + 0.5 + poses[mid].x / res, y0 + 0.5 + poses[mid].y / res,
                   std::max(before, after) / res)) {
    return true;
  }
  if (last - first > 1) {
    return sweepFree(x0, y0, poses, first, mid, scratch) &&
           sweepFree(x0, y0, poses, mid, last, scratch);
  }
  // One step: the cells primitiveCells would give it, rasterised only for the edges with a
  // blocked cell near them (then the exact cells decide).
  std::vector<CellPoint>& prev = scratch.prev;
  std::vector<CellPoint>& cur = scratch.cur;
  std::vector<CellOffset>& cells = scratch.cells;
  std::vector<std::size_t>& near = scratch.near;
  const Pose2D& a = poses[first];
  const Pose2D& b = poses[last];
  footprintInCells(f, a, res, prev);
  // No vertex moves farther than the step's length plus its radius times the turn: a box that
  // far around an edge's first position holds all of its positions in the step.
  const double move = (std::hypot(b.x - a.x, b.y - a.y) +
                       f.circumscribed_radius * std::fabs(smallAngle(b.theta - a.theta))) /
                      res;
  const std::size_t vertices = prev.size();
  near.clear();
  for (std::size_t e = 0; e < vertices; ++e) {
    const std::array<CellPoint, 2> edge{prev[e], prev[(e + 1) % vertices]};
    if (boxBlocked(m, x0, y0, CellBox::around(edge, edge, move))) near.push_back(e);
  }
  if (near.empty()) return true;
  const int steps = sweepSteps(f, a, b, res);
  // A straight step keeps its heading: its placements share one sine and cosine.
  const bool straight = a.theta == b.theta;
  const double cos_a = std::cos(a.theta), sin_a = std::sin(a.theta);
  for (int s = 1; s <= steps; ++s) {
    const Pose2D sample = sweepSample(a, b, s, steps);
    if (straight) {
      footprintInCells(f, sample, res, cur, cos_a, sin_a);
    } else {
      footprintInCells(f, sample, res, cur);
    }
    for (std::size_t e : near) {
      const std::array<CellPoint, 2> from{prev[e], prev[(e + 1) % vertices]},
          to{cur[e], cur[(e + 1) % vertices]};
      if (!boxBlocked(m, x0, y0, CellBox::around(from, to))) continue;
      cells.clear();
      rasterizeEdgeSweep(prev, cur, e, cells);
      for (const CellOffset& o : cells) {
        const int cx = x0 + o.dx, cy = y0 + o.dy;
        if (cx < 0 || cy < 0 || cx >= m.width || cy >= m.height || m.at(cx, cy) >= kLethalCost)
          return false;
      }
    }
    std::swap(prev, cur);
  }
  return true;
}

Cost PathSmoother::shortcutCost(int x0, int y0, const std::vector<Pose2D>& poses, double multiplier,
                                Cost budget, std::vector<SmoothedPiece>* pieces,
                                Scratch& scratch) const {
  const GridMap& m = graph_.map();
  const double res = m.resolution;
  const LatticeConfig& c = graph_.config();
  if (poses.size() < 2) return kInvalidEdge;
  std::vector<CellOffset>& cells = scratch.cells;
  std::vector<double>& along = scratch.along;
  along.assign(1, 0.0);
  const RobotFootprint& f = graph_.footprint();
  if (!f.polygon.empty()) {
    // The footprint at the first pose, as primitiveCells has it.
    footprintInCells(f, poses.front(), res, scratch.prev);
    if (boxBlocked(m, x0, y0, CellBox::around(scratch.prev, scratch.prev))) {
      cells.clear();
      rasterizePolygon(scratch.prev, cells);
      for (const CellOffset& o : cells) {
        const int cx = x0 + o.dx, cy = y0 + o.dy;
        if (cx < 0 || cy < 0 || cx >= m.width || cy >= m.height || m.at(cx, cy) >= kLethalCost)
          return kInvalidEdge;
      }
    }
  }
  Cost total = 0;
  std::size_t first = 0;
  while (first + 1 < poses.size()) {
    // A piece: as many steps as fit in piece_length_ (at least one).
    double length = 0.0, turn = 0.0;
    unsigned worst = 0;
    std::size_t last = first;
    while (last + 1 < poses.size()) {
      const Pose2D& a = poses[last];
      const Pose2D& b = poses[last + 1];
      const double step = std::sqrt((b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y));
      if (last > first && length + step > piece_length_ * (1.0 + 1e-9)) break;
      length += step;
      along.push_back(along.back() + step);
      turn += std::fabs(smallAngle(b.theta - a.theta));
      const CellPoint pa{a.x / res + 0.5, a.y / res + 0.5}, pb{b.x / res + 0.5, b.y / res + 0.5};
      // The centre's cells; rasterised only if a box around them could change the verdict or
      // the worst cost.
      const CellBox box(std::min(pa.x, pb.x), std::max(pa.x, pb.x), std::min(pa.y, pb.y),
                        std::max(pa.y, pb.y));
      bool exact =
          x0 + box.i0 < 0 || y0 + box.j0 < 0 || x0 + box.i1 >= m.width || y0 + box.j1 >= m.height;
      for (int j = box.j0; j <= box.j1 && !exact; ++j) {
        for (int i = box.i0; i <= box.i1 && !exact; ++i) exact = m.at(x0 + i, y0 + j) > worst;
      }
      if (exact) {
        cells.clear();
        rasterizeSegment(pa, pb, cells);
        for (const CellOffset& o : cells) {
          const int cx = x0 + o.dx, cy = y0 + o.dy;
          if (cx < 0 || cy < 0 || cx >= m.width || cy >= m.height) return kInvalidEdge;
          const unsigned v = m.at(cx, cy);
          if (v >= kInscribedCost) return kInvalidEdge;
          worst = std::max(worst, v);
        }
      }
      ++last;
    }
    const double turn_as_distance = omega_ > 0.0 ? c.cost.nominal_speed * turn / omega_ : 0.0;
    const double units = std::ceil(kCostUnitsPerMetre * std::max(length, turn_as_distance) - 1e-6);
    const Cost base = std::max<Cost>(1, std::llround(units * multiplier));
    const Cost cost = graph_.costWithPenalty(base, worst);
    total += cost;
    if (total > budget) return kInvalidEdge;
    // The piece's sweep now, so that a collision ends a hopeless trial early.
    if (!f.polygon.empty() && !sweepFree(x0, y0, poses, first, last, scratch)) return kInvalidEdge;
    if (pieces != nullptr) {
      SmoothedPiece piece;
      piece.first = first;
      piece.last = last;
      piece.shortcut = true;
      piece.multiplier = multiplier;
      piece.cost = cost;
      pieces->push_back(piece);
    }
    first = last;
  }
  return total;
}

Cost PathSmoother::motionCost(int x, int y, const std::vector<Pose2D>& poses,
                              double multiplier) const {
  Scratch scratch;
  return shortcutCost(x, y, poses, multiplier, std::numeric_limits<Cost>::max(), nullptr, scratch);
}

bool PathSmoother::tryShortcut(const Pose2D& a_grid, const Pose2D& b_grid, int x0, int y0,
                               bool backward, double radius, double multiplier, Cost budget,
                               Candidate& out, Scratch& scratch) const {
  const double res = graph_.map().resolution;
  // From the input's pose where motion i starts to its pose where motion j - 1 ends (a file's
  // motions may end a little off the state's centre and heading: the curve meets them there),
  // relative to the first state's cell centre; travel directions for Dubins.
  const double cx = (x0 + 0.5) * res, cy = (y0 + 0.5) * res, flip = backward ? M_PI : 0.0;
  const Pose2D a{a_grid.x - cx, a_grid.y - cy, a_grid.theta + flip};
  const Pose2D b{b_grid.x - cx, b_grid.y - cy, b_grid.theta + flip};
  const DubinsPath path = shortestDubinsPath(a, b, radius);
  // Hopeless by length alone (the poses' chords are within 1 % of the arcs; each piece rounds
  // up by less than a unit): no need to look at the map.
  const double pieces = std::ceil(path.totalLength() / piece_length_) + 1.0;
  if (0.99 * kCostUnitsPerMetre * path.totalLength() * multiplier - 2.0 * pieces >
      static_cast<double>(budget))
    return false;
  // A pose per cell (the generated primitives have two; arcs of the turning radius deviate
  // from their chords by less than a hundredth of a cell at 5 cm cells and 0.3 m).
  sampleDubinsPath(path, res, out.poses);
  for (Pose2D& p : out.poses) p.theta -= flip;
  out.poses.front() = {a.x, a.y, a_grid.theta};
  out.poses.back() = {b.x, b.y, b_grid.theta};
  out.pieces.clear();
  out.cost = shortcutCost(x0, y0, out.poses, multiplier, budget, &out.pieces, scratch);
  return out.cost != kInvalidEdge;
}

SmoothedPath PathSmoother::smooth(const std::vector<Pose2D>& input) const {
  const auto t0 = std::chrono::steady_clock::now();
  SmoothedPath out;
  out.turning_radius = radius_;
  if (input.empty()) throw std::invalid_argument("lattice path: no poses");
  std::vector<Pose2D> grid;
  const std::vector<Edge> edges = parse(input, grid);
  for (const Edge& e : edges) out.lattice_cost += e.cost;
  out.poses.push_back(input.front());

  auto keep = [&](const Edge& e) {
    SmoothedPiece piece;
    piece.first = out.poses.size() - 1;
    out.poses.insert(out.poses.end(), input.begin() + static_cast<std::ptrdiff_t>(e.first) + 1,
                     input.begin() + static_cast<std::ptrdiff_t>(e.last) + 1);
    piece.last = out.poses.size() - 1;
    piece.backward = actions_[e.action].motion == MotionKind::kBackward;
    piece.primitive = graph_.actions()[e.action].primitive;
    piece.multiplier = actions_[e.action].multiplier;
    piece.cost = e.cost;
    out.pieces.push_back(piece);
    out.cost += e.cost;
  };
  auto take = [&](const Edge& from, const Candidate& c, bool backward) {
    const std::size_t offset = out.poses.size() - 1;
    for (std::size_t k = 1; k + 1 < c.poses.size(); ++k)
      out.poses.push_back(graph_.cellPoseToMap(from.x, from.y, c.poses[k]));
    out.poses.push_back(input[edges[c.to_edge].last]);  // the input's own pose of that state
    for (SmoothedPiece piece : c.pieces) {
      piece.first += offset;
      piece.last += offset;
      piece.backward = backward;
      out.pieces.push_back(piece);
    }
    out.cost += c.cost;
    ++out.shortcuts;
  };

  Candidate found, trial;
  Scratch scratch;
  for (std::size_t begin = 0; begin < edges.size();) {
    const MotionKind motion = actions_[edges[begin].action].motion;
    std::size_t end = begin + 1;  // a driving stretch: [begin, end)
    if (motion == MotionKind::kForward || motion == MotionKind::kBackward) {
      while (end < edges.size() && actions_[edges[end].action].motion == motion) ++end;
    }
    const bool backward = motion == MotionKind::kBackward;
    std::size_t i = begin;
    while (i < end) {
      // Shortcut from edge i's start to edge j - 1's end, replacing edges [i, j).
      auto attempt = [&](std::size_t j, double radius, Candidate& c) {
        Cost budget = 0;
        double multiplier = 0.0;
        for (std::size_t k = i; k < j; ++k) {
          budget += edges[k].cost;
          multiplier = std::max(multiplier, actions_[edges[k].action].multiplier);
        }
        c.to_edge = j - 1;
        return tryShortcut(grid[edges[i].first], grid[edges[j - 1].last], edges[i].x, edges[i].y,
                           backward, radius, multiplier, budget, c, scratch);
      };
      std::size_t ok = i + 1, fail = end + 1;  // replacing [i, ok) works, [i, fail) does not
      if ((motion == MotionKind::kForward || motion == MotionKind::kBackward) &&
          std::isfinite(radius_)) {
        // Doubling, then bisection (the farthest reachable state, as far as the probes see).
        for (std::size_t j = i + 2; j <= end; j = std::min(end, i + 2 * (j - i))) {
          if (!attempt(j, radius_, trial)) {
            fail = j;
            break;
          }
          ok = j;
          std::swap(found, trial);
          if (j == end) break;
        }
        while (fail - ok > 1 && fail <= end) {
          const std::size_t mid = ok + (fail - ok) / 2;
          if (attempt(mid, radius_, trial)) {
            ok = mid;
            std::swap(found, trial);
          } else {
            fail = mid;
          }
        }
      }
      if (ok < i + 2) {
        keep(edges[i]);
        ++i;
        continue;
      }
      take(edges[i], found, backward);
      i = ok;
    }
    begin = end;
  }
  if (out.cost > out.lattice_cost)
    throw std::logic_error("path smoother: the smoothed path costs more than the lattice path");
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

LatticeSolution smoothedSolution(const LatticeSolution& raw, const SmoothedPath& smoothed) {
  LatticeSolution s = raw;
  s.poses = smoothed.poses;
  s.search.cost = smoothed.cost;
  if (raw.search.cost > 0) {
    const double scaled = raw.search.certified_bound * static_cast<double>(smoothed.cost) /
                          static_cast<double>(raw.search.cost);
    s.search.certified_bound = std::min(std::max(scaled, 1.0), raw.search.nominal_bound);
  }
  return s;
}

SmoothedPath SmoothedStream::smoothAfterEscape(const LatticeSolution& raw) const {
  // The escape's motions cross the inscribed and obstacle cells the start stands on, which the
  // smoother's collision test refuses by design: they are kept as they are, and the rest of the
  // path, from the first collision-free pose on, is smoothed. The cost is the escape's plus the
  // rest's, so it stays at most the search's.
  const std::size_t k = raw.escape_poses - 1;  // the first collision-free pose
  if (k >= raw.poses.size()) throw std::invalid_argument("escape_poses beyond the path");
  SmoothedPath out;
  if (raw.poses.size() - k >= 2) {
    out = smoother_.smooth(
        std::vector<Pose2D>(raw.poses.begin() + static_cast<std::ptrdiff_t>(k), raw.poses.end()));
  } else {
    out.poses.assign(1, raw.poses.back());
  }
  out.poses.insert(out.poses.begin(), raw.poses.begin(),
                   raw.poses.begin() + static_cast<std::ptrdiff_t>(k));
  out.cost += raw.escape_cost;
  out.lattice_cost += raw.escape_cost;
  return out;
}

const SmoothedStream::Step& SmoothedStream::add(const LatticeSolution& raw) {
  // A-MHA* and ARA* report a path again when only its bound tightens: smoothed once.
  if (!started_ || raw.search.path != last_ids_) {
    step_.smoothed = raw.escape_poses > 0 ? smoothAfterEscape(raw) : smoother_.smooth(raw.poses);
    last_ids_ = raw.search.path;
  }
  LatticeSolution own = smoothedSolution(raw, step_.smoothed);
  const bool earlier_cheaper = started_ && step_.published.search.cost < own.search.cost;
  if (earlier_cheaper) {
    // The earlier path with this solution's bounds (both hold for it, see above).
    LatticeSolution kept = raw;
    kept.poses = step_.published.poses;
    kept.search.cost = step_.published.search.cost;
    const double scaled = raw.search.certified_bound * static_cast<double>(kept.search.cost) /
                          static_cast<double>(std::max<Cost>(raw.search.cost, 1));
    kept.search.certified_bound =
        std::min(step_.published.search.certified_bound,
                 std::min(std::max(scaled, 1.0), raw.search.nominal_bound));
    step_.published = std::move(kept);
    step_.same_as_previous = true;
  } else {
    step_.same_as_previous =
        started_ && own.poses.size() == step_.published.poses.size() &&
        std::equal(own.poses.begin(), own.poses.end(), step_.published.poses.begin(),
                   [](const Pose2D& a, const Pose2D& b) {
                     return a.x == b.x && a.y == b.y && a.theta == b.theta;
                   });
    // Costs do not rise, so the previous certified bound holds for this path too.
    if (started_)
      own.search.certified_bound =
          std::min(own.search.certified_bound, step_.published.search.certified_bound);
    step_.published = std::move(own);
  }
  step_.republished = earlier_cheaper;
  started_ = true;
  return step_;
}

}  // namespace lattice
}  // namespace amha
