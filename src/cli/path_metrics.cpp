#include "path_metrics.h"

#include <algorithm>
#include <cmath>

namespace amha {
namespace cli {

// Below this curvature (1/m: a radius of a kilometre) a step counts as straight, so that
// rounding does not count as turning left or right.
constexpr double kStraight = 1e-3;

PathMetrics pathMetrics(const std::vector<lattice::Pose2D>& poses) {
  PathMetrics m;
  double turned = 0.0, bent = 0.0;
  int last_sign = 0;
  for (std::size_t k = 1; k < poses.size(); ++k) {
    const lattice::Pose2D& a = poses[k - 1];
    const lattice::Pose2D& b = poses[k];
    const double chord = std::hypot(b.x - a.x, b.y - a.y);
    const double dth = std::remainder(b.theta - a.theta, 2.0 * M_PI);
    turned += std::fabs(dth);
    if (chord < 1e-9) continue;
    const double curvature = 2.0 * std::sin(0.5 * std::fabs(dth)) / chord;
    m.length += chord;
    bent += curvature * chord;
    m.max_curvature = std::max(m.max_curvature, curvature);
    if (curvature < kStraight) continue;  // straight: no side
    const int sign = dth > 0.0 ? 1 : -1;
    m.curvature_sign_changes += last_sign != 0 && sign != last_sign;
    last_sign = sign;
  }
  if (m.length > 0.0) {
    m.mean_curvature = bent / m.length;
    m.heading_change_per_metre = turned / m.length;
  }
  return m;
}

}  // namespace cli
}  // namespace amha
