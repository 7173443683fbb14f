// SBPL .mprim reader with full validation (format: ../shared/data/README.md, SBPL's
// EnvironmentNAVXYTHETALATTICE::ReadMotionPrimitives).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "amha_planner/lattice/motion_primitives.h"
#include "primitive_geometry.h"
#include "tokenizer.h"

namespace amha {
namespace lattice {

namespace {

std::string str(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// floor(v) as an int, clamped (a pose far outside int range would otherwise be undefined).
int floorDiv(double v) { return static_cast<int>(std::max(-2e9, std::min(2e9, std::floor(v)))); }

// .mprim files do not say which part of a primitive is an arc, nor whether it drives
// backwards: estimated from the poses (for writing Nav2 files).
void describeShape(const PrimitiveSet& set, MotionPrimitive& p) {
  const double length = detail::polylineLength(p.poses);
  const double turn =
      angleDistance(set.heading_angles[p.start_heading], set.heading_angles[p.end_heading]);
  p.arc_length =
      p.turning_radius != 0.0 ? std::min(length, std::fabs(p.turning_radius) * turn) : 0.0;
  p.straight_length = length - p.arc_length;
  const double phi = set.heading_angles[p.start_heading];
  for (std::size_t k = 1; k < p.poses.size(); ++k) {
    const double dx = p.poses[k].x - p.poses[0].x, dy = p.poses[k].y - p.poses[0].y;
    if (std::hypot(dx, dy) < 1e-9) continue;
    p.reverse = dx * std::cos(phi) + dy * std::sin(phi) < -0.5 * std::hypot(dx, dy);
    break;
  }
}

}  // namespace

PrimitiveSet readMprim(std::istream& in, const std::string& name, double map_resolution) {
  detail::Tokenizer t(in, name, LatticeError::Kind::kPrimitives);
  PrimitiveSet set;

  t.expect("resolution_m:");
  set.resolution = t.number("the resolution");
  if (!(set.resolution > 0.0)) t.fail("resolution " + str(set.resolution) + " is not positive");
  if (map_resolution > 0.0 && std::fabs(set.resolution - map_resolution) > 1e-6) {
    t.fail("resolution " + str(set.resolution) + " in file != map " + str(map_resolution));
  }
  std::string label = t.next();
  if (label == "min_turning_radius_m:") {
    set.uniform = false;
    set.min_turning_radius = t.number("the minimum turning radius");
    if (set.min_turning_radius < 0.0) t.fail("min_turning_radius_m must not be negative");
    label = t.next();
  }
  if (label != "numberofangles:") t.fail("expected 'numberofangles:' but found '" + label + "'");
  const long n = t.integer("the number of angles");
  if (n < 1 || n > 1024) t.fail("numberofangles " + std::to_string(n) + " is not in 1..1024");
  set.num_headings = static_cast<int>(n);
  set.heading_angles.resize(n);
  if (set.uniform) {
    for (int i = 0; i < n; ++i) set.heading_angles[i] = 2.0 * M_PI * i / n;
  } else {
    for (int i = 0; i < n; ++i) {
      t.expect("angle:" + std::to_string(i));
      const double a = t.number("an angle in radians");
      if (a < 0.0 || a >= 2.0 * M_PI)
        t.fail("angle " + str(a) + " of heading " + std::to_string(i) + " is not in [0, 2 pi)");
      if (i > 0 && a <= set.heading_angles[i - 1])
        t.fail("heading angles must increase (angle:" + std::to_string(i) + ")");
      set.heading_angles[i] = a;
    }
  }
  t.expect("totalnumberofprimitives:");
  const long total = t.integer("the number of primitives");
  if (total < 1 || total > 1000000)
    t.fail("totalnumberofprimitives " + std::to_string(total) + " is not in 1..1000000");

  const double res = set.resolution;
  set.primitives.reserve(total);
  for (long k = 0; k < total; ++k) {
    MotionPrimitive p;
    const std::string what = "primitive " + std::to_string(k + 1) + " of " + std::to_string(total);
    const std::string l = t.next();
    if (l.empty()) t.fail("file ends before " + what);
    if (l != "primID:") t.fail("expected 'primID:' (" + what + ") but found '" + l + "'");
    const int prim_line = t.tokenLine();
    const long id = t.integer("primID");
    if (id < 0) t.fail("primID " + std::to_string(id) + " is negative");
    p.id = static_cast<int>(id);
    t.expect("startangle_c:");
    const long a = t.integer("startangle_c");
    if (a < 0 || a >= n)
      t.fail("startangle_c " + std::to_string(a) + " is not in 0.." + std::to_string(n - 1));
    p.start_heading = static_cast<int>(a);
    t.expect("endpose_c:");
    const long dx = t.integer("endpose_c x"), dy = t.integer("endpose_c y");
    const long et = t.integer("endpose_c theta");
    if (std::labs(dx) > 100000 || std::labs(dy) > 100000) t.fail("endpose_c is implausibly far");
    p.end_dx = static_cast<int>(dx);
    p.end_dy = static_cast<int>(dy);
    p.end_heading = static_cast<int>(((et % n) + n) % n);
    t.expect("additionalactioncostmult:");
    p.cost_multiplier = t.number("additionalactioncostmult");
    if (!(p.cost_multiplier > 0.0))
      t.fail("additionalactioncostmult " + str(p.cost_multiplier) + " must be positive");
    if (!set.uniform) {
      t.expect("turning_radius:");
      p.turning_radius = t.number("turning_radius");  // signed in SBPL's files: < 0 turns right
    }
    t.expect("intermediateposes:");
    const long count = t.integer("the number of intermediate poses");
    if (count < 1 || count > 100000)
      t.fail("intermediateposes " + std::to_string(count) + " is not in 1..100000");
    p.poses.resize(count);
    for (long i = 0; i < count; ++i) {
      Pose2D& q = p.poses[i];
      q.x = t.number("an intermediate x");
      q.y = t.number("an intermediate y");
      q.theta = t.number("an intermediate theta");
    }
    const int pose_line = t.tokenLine();
    const double length = detail::polylineLength(p.poses);
    if (!(length / res <= detail::kMaxPrimitiveCells)) {
      t.failAt(pose_line, "primID " + std::to_string(p.id) + " (start heading " +
                              std::to_string(p.start_heading) + "): its intermediate poses are " +
                              str(length / res) + " cells long (at most " +
                              str(detail::kMaxPrimitiveCells) + ")");
    }
    // The first pose is the start cell's centre at the start heading.
    const Pose2D& first = p.poses.front();
    if (floorDiv((0.5 * res + first.x) / res) != 0 || floorDiv((0.5 * res + first.y) / res) != 0 ||
        set.headingIndex(first.theta) != p.start_heading) {
      t.failAt(prim_line, "primID " + std::to_string(p.id) + " (start heading " +
                              std::to_string(p.start_heading) + "): first intermediate pose " +
                              str(first.x) + " " + str(first.y) + " " + str(first.theta) +
                              " is not in the start cell at the start heading");
    }
    // The last pose must discretise to endpose_c (SBPL's check, in cells from the centre).
    const Pose2D& last = p.poses.back();
    const int ex = floorDiv((0.5 * res + last.x) / res), ey = floorDiv((0.5 * res + last.y) / res);
    const int eh = set.headingIndex(last.theta);
    if (ex != p.end_dx || ey != p.end_dy || eh != p.end_heading) {
      t.failAt(pose_line, "primID " + std::to_string(p.id) + " (start heading " +
                              std::to_string(p.start_heading) + "): last intermediate pose " +
                              str(last.x) + " " + str(last.y) + " " + str(last.theta) +
                              " discretises to " + std::to_string(ex) + " " + std::to_string(ey) +
                              " " + std::to_string(eh) + ", not endpose_c " +
                              std::to_string(p.end_dx) + " " + std::to_string(p.end_dy) + " " +
                              std::to_string(p.end_heading));
    }
    set.primitives.push_back(std::move(p));
  }
  const std::string extra = t.next();
  if (!extra.empty()) t.fail("unexpected '" + extra + "' after the last primitive");

  std::stable_sort(set.primitives.begin(), set.primitives.end(),
                   [](const MotionPrimitive& a, const MotionPrimitive& b) {
                     return a.start_heading < b.start_heading;
                   });
  const std::size_t per = set.primitives.size() / n;
  for (int h = 0; h < n; ++h) {
    const auto r = set.range(h);
    if (r.second - r.first != per || set.primitives.size() % n != 0) {
      t.fail("heading " + std::to_string(h) + " has " + std::to_string(r.second - r.first) +
             " primitives; every heading needs the same number (" + std::to_string(total) + " / " +
             std::to_string(n) + ")");
    }
    for (std::size_t i = r.first; i < r.second; ++i) {
      for (std::size_t j = r.first; j < i; ++j) {
        if (set.primitives[i].id == set.primitives[j].id) {
          t.fail("primID " + std::to_string(set.primitives[i].id) +
                 " appears twice for start heading " + std::to_string(h));
        }
      }
    }
  }
  for (MotionPrimitive& p : set.primitives) describeShape(set, p);
  detail::dropCopies(set);
  return set;
}

PrimitiveSet readMprimFile(const std::string& path, double map_resolution) {
  std::ifstream in(path);
  if (!in) throw LatticeError(LatticeError::Kind::kPrimitives, path + ": cannot open the file");
  return readMprim(in, path, map_resolution);
}

}  // namespace lattice
}  // namespace amha
