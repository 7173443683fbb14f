// Dubins paths by construction: the circles of the turns at both ends, the tangent lines (CSC)
// or the third circle touching both (CCC) between them, then each candidate followed to its end.
#include "amha_planner/lattice/detail/dubins_path.h"

#include <cmath>
#include <limits>

namespace amha {
namespace lattice {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;

/// Angle in [0, 2 pi), with turns within 1e-9 of a full one counted as none (rounding must not
/// turn "no turn" into a loop).
double turnAngle(double a) {
  double t = std::fmod(a, kTwoPi);
  if (t < 0.0) t += kTwoPi;
  if (t > kTwoPi - 1e-9 || t < 1e-9) t = 0.0;
  return t;
}

struct Point {
  double x, y;
};

/// Centre of the circle of radius r the robot turns on at pose p (side +1 left, -1 right).
Point centre(const Pose2D& p, int side, double r) {
  return {p.x - side * r * std::sin(p.theta), p.y + side * r * std::cos(p.theta)};
}

Pose2D follow(const Pose2D& p, int turn, double length, double r) {
  if (turn == 0)
    return {p.x + length * std::cos(p.theta), p.y + length * std::sin(p.theta), p.theta};
  const double k = turn / r;
  const double th = p.theta + k * length;
  return {p.x + (std::sin(th) - std::sin(p.theta)) / k,
          p.y + (std::cos(p.theta) - std::cos(th)) / k, th};
}

}  // namespace

Pose2D DubinsPath::at(double s) const {
  Pose2D p = start;
  s = std::max(0.0, s);
  for (int k = 0; k < 3; ++k) {
    const double l = std::min(s, length[k]);
    p = follow(p, turn[k], l, radius);
    s -= l;
    if (s <= 0.0) break;
  }
  return p;
}

DubinsPath shortestDubinsPath(const Pose2D& from, const Pose2D& to, double r) {
  DubinsPath best;
  best.start = from;
  best.radius = r;
  double best_length = std::numeric_limits<double>::infinity();
  // Angles are turn amounts (radians) for arcs; the straight piece's length is in metres.
  auto consider = [&](int t0, double a0, int t1, double a1, int t2, double a2) {
    DubinsPath c;
    c.start = from;
    c.radius = r;
    c.turn = {t0, t1, t2};
    c.length = {t0 != 0 ? a0 * r : a0, t1 != 0 ? a1 * r : a1, t2 != 0 ? a2 * r : a2};
    const double total = c.totalLength();
    if (!(total < best_length)) return;
    const Pose2D end = c.at(total);
    if (std::hypot(end.x - to.x, end.y - to.y) > 1e-6 * r + 1e-9 ||
        std::fabs(std::remainder(end.theta - to.theta, kTwoPi)) > 1e-6) {
      return;  // this word does not reach `to` (a degenerate case)
    }
    best = c;
    best_length = total;
  };
  const double th0 = from.theta, th1 = to.theta;
  // Same-side turns: CSC along the outer tangent, CCC through a third circle.
  for (int side : {+1, -1}) {
    const Point c1 = centre(from, side, r), c2 = centre(to, side, r);
    const double dx = c2.x - c1.x, dy = c2.y - c1.y, d = std::hypot(dx, dy);
    const double psi = d > 0.0 ? std::atan2(dy, dx) : th0;  // heading along the tangent
    consider(side, turnAngle(side * (psi - th0)), 0, d, side, turnAngle(side * (th1 - psi)));
    if (d < 4.0 * r && d > 0.0) {
      const double h = std::sqrt(4.0 * r * r - 0.25 * d * d);
      for (int branch : {+1, -1}) {
        const Point c3{c1.x + 0.5 * dx - branch * h * dy / d,
                       c1.y + 0.5 * dy + branch * h * dx / d};
        // Where the circles touch, the heading is perpendicular to the line of centres.
        const double psi1 = std::atan2(c3.y - c1.y, c3.x - c1.x) + side * M_PI / 2.0;
        const double psi2 = std::atan2(c3.y - c2.y, c3.x - c2.x) + side * M_PI / 2.0;
        consider(side, turnAngle(side * (psi1 - th0)), -side, turnAngle(side * (psi1 - psi2)), side,
                 turnAngle(side * (th1 - psi2)));
      }
    }
  }
  // Opposite turns: CSC along an inner tangent.
  for (int side : {+1, -1}) {
    const Point c1 = centre(from, side, r), c2 = centre(to, -side, r);
    const double dx = c2.x - c1.x, dy = c2.y - c1.y, d = std::hypot(dx, dy);
    if (d < 2.0 * r) continue;
    const double psi = std::atan2(dy, dx) + side * std::asin(2.0 * r / d);
    consider(side, turnAngle(side * (psi - th0)), 0, std::sqrt(d * d - 4.0 * r * r), -side,
             turnAngle(-side * (th1 - psi)));
  }
  return best;
}

void sampleDubinsPath(const DubinsPath& path, double spacing, std::vector<Pose2D>& out) {
  const double total = path.totalLength();
  const int count = std::max(2, static_cast<int>(std::ceil(total / spacing)) + 1);
  out.resize(count);
  // Piece by piece from each piece's start pose (its sine and cosine computed once): one sine
  // and cosine per sample on arcs, none on straight lines.
  Pose2D p0 = path.start;
  double s0 = 0.0, c0 = std::cos(p0.theta), n0 = std::sin(p0.theta);
  int piece = 0;
  for (int i = 0; i < count; ++i) {
    const double s = total * i / (count - 1);
    while (piece < 2 && s > s0 + path.length[piece]) {
      p0 = follow(p0, path.turn[piece], path.length[piece], path.radius);
      s0 += path.length[piece];
      c0 = std::cos(p0.theta);
      n0 = std::sin(p0.theta);
      ++piece;
    }
    const double l = std::min(s - s0, path.length[piece]);
    if (path.turn[piece] == 0) {
      out[i] = {p0.x + l * c0, p0.y + l * n0, p0.theta};
    } else {
      const double k = path.turn[piece] / path.radius, th = p0.theta + k * l;
      out[i] = {p0.x + (std::sin(th) - n0) / k, p0.y + (c0 - std::cos(th)) / k, th};
    }
  }
}

}  // namespace lattice
}  // namespace amha
