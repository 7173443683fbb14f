// Geometry and set handling shared by the primitive generators and readers (primitive_geometry.h).
#include "primitive_geometry.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>

namespace amha {
namespace lattice {
namespace detail {

double polylineLength(const std::vector<Pose2D>& poses) {
  double length = 0.0;
  for (std::size_t k = 1; k < poses.size(); ++k) {
    length += std::hypot(poses[k].x - poses[k - 1].x, poses[k].y - poses[k - 1].y);
  }
  return length;
}

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
  throw LatticeError(LatticeError::Kind::kConfig,
                     "primitive generator: cannot choose lattice directions for " +
                         std::to_string(n) + " headings");
}

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

void generatorError(const std::string& what) {
  throw LatticeError(LatticeError::Kind::kConfig, "primitive generator: " + what);
}

int directionIndex(const std::vector<Vec>& dirs, Vec v) {
  const int g = std::gcd(std::abs(v.x), std::abs(v.y));
  if (g > 0) v = {v.x / g, v.y / g};
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    if (dirs[i].x == v.x && dirs[i].y == v.y) return static_cast<int>(i);
  }
  generatorError("internal: direction not on the lattice");
}

void validateGeneratorOptions(const PrimitiveGeneratorOptions& o) {
  const auto fail = generatorError;
  if (!(o.resolution > 0.0) || !std::isfinite(o.resolution)) fail("resolution must be positive");
  if (o.num_headings < 8 || o.num_headings % 8 != 0 || o.num_headings > 256) {
    fail("the number of headings must be a multiple of 8 in 8..256, not " +
         std::to_string(o.num_headings));
  }
  if (!(o.turning_radius > 0.0) || !std::isfinite(o.turning_radius))
    fail("the turning radius must be positive");
  if (!(o.reverse_multiplier > 0) || !(o.turn_in_place_multiplier > 0) ||
      !std::isfinite(o.reverse_multiplier) || !std::isfinite(o.turn_in_place_multiplier)) {
    fail("cost multipliers must be positive");
  }
}

PrimitiveSet latticeSet(const PrimitiveGeneratorOptions& o, const std::vector<Vec>& dirs) {
  PrimitiveSet set;
  set.resolution = o.resolution;
  set.num_headings = static_cast<int>(dirs.size());
  set.uniform = set.num_headings == 8;  // 8 lattice directions are 45 degrees apart
  set.min_turning_radius = o.turning_radius;
  for (const Vec& v : dirs) set.heading_angles.push_back(normalizeAngle(std::atan2(v.y, v.x)));
  const bool turns = o.turn_in_place && o.motion_model != MotionModel::kAckermann;
  set.motion_model = o.motion_model == MotionModel::kOmni ? "omni" : turns ? "diff" : "ackermann";
  return set;
}

Vec Symmetry::apply(Vec v) const {
  if (reflect) std::swap(v.x, v.y);
  for (int r = 0; r < quarter; ++r) v = {-v.y, v.x};
  return v;
}

Pose2D Symmetry::apply(const Pose2D& p) const {
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

MotionPrimitive turnOnTheSpot(const PrimitiveSet& set, int h, int side, double multiplier) {
  const int n = set.num_headings, h1 = (h + side + n) % n;
  const double phi = set.heading_angles[h],
               d = std::remainder(set.heading_angles[h1] - phi, 2.0 * M_PI);
  MotionPrimitive p;
  p.start_heading = h;
  p.end_heading = h1;
  p.cost_multiplier = multiplier;
  for (int i = 0; i <= 4; ++i) p.poses.push_back({0.0, 0.0, normalizeAngle(phi + d * i / 4.0)});
  return p;
}

MotionPrimitive transformed(const MotionPrimitive& bp, const Symmetry& g, int start,
                            const std::vector<Vec>& dirs, const PrimitiveSet& set) {
  MotionPrimitive p = bp;
  p.start_heading = start;
  const Vec e = g.apply(Vec{bp.end_dx, bp.end_dy});
  p.end_dx = e.x;
  p.end_dy = e.y;
  p.end_heading = directionIndex(dirs, g.apply(dirs[bp.end_heading]));
  if (g.reflect) p.turning_radius = -p.turning_radius;  // a mirror swaps left and right
  for (Pose2D& q : p.poses) q = g.apply(q);
  const double res = set.resolution;
  p.poses.front() = {0.0, 0.0, set.heading_angles[start]};
  p.poses.back() = {e.x * res, e.y * res, set.heading_angles[p.end_heading]};
  for (Pose2D& q : p.poses) q.theta = normalizeAngle(q.theta);
  return p;
}

void numberByHeading(PrimitiveSet& set) {
  std::stable_sort(set.primitives.begin(), set.primitives.end(),
                   [](const MotionPrimitive& a, const MotionPrimitive& b) {
                     return a.start_heading < b.start_heading;
                   });
  for (std::size_t i = 0; i < set.primitives.size(); ++i) {
    const bool first =
        i == 0 || set.primitives[i - 1].start_heading != set.primitives[i].start_heading;
    set.primitives[i].id = first ? 0 : set.primitives[i - 1].id + 1;
  }
}

namespace {

bool samePoses(const std::vector<Pose2D>& a, const std::vector<Pose2D>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (a[k].x != b[k].x || a[k].y != b[k].y || a[k].theta != b[k].theta) return false;
  }
  return true;
}

}  // namespace

void dropCopies(PrimitiveSet& set) {
  // Hashed, so that a file of many primitives is not compared pair by pair.
  auto hashOf = [](const MotionPrimitive& p) {
    std::uint64_t h = 1469598103934665603ull;
    auto mix = [&h](const void* data, std::size_t n) {
      const auto* b = static_cast<const unsigned char*>(data);
      for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
    };
    const int ends[3] = {p.end_dx, p.end_dy, p.end_heading};
    mix(ends, sizeof ends);
    mix(&p.cost_multiplier, sizeof(double));
    for (const Pose2D& q : p.poses) mix(&q, sizeof q);
    return h;
  };
  std::vector<MotionPrimitive> kept;
  for (int h = 0; h < set.num_headings; ++h) {
    std::unordered_map<std::uint64_t, std::vector<std::size_t>> seen;
    const auto r = set.range(h);
    for (std::size_t i = r.first; i < r.second; ++i) {
      const MotionPrimitive& p = set.primitives[i];
      std::vector<std::size_t>& same_hash = seen[hashOf(p)];
      bool copy = false;
      for (std::size_t j : same_hash) {
        const MotionPrimitive& q = kept[j];
        copy = copy || (q.end_dx == p.end_dx && q.end_dy == p.end_dy &&
                        q.end_heading == p.end_heading && q.cost_multiplier == p.cost_multiplier &&
                        q.turning_radius == p.turning_radius && samePoses(q.poses, p.poses));
      }
      if (copy) continue;
      same_hash.push_back(kept.size());
      kept.push_back(p);
    }
  }
  set.primitives = std::move(kept);
}

}  // namespace detail
}  // namespace lattice
}  // namespace amha
