// Heading discretisation of a primitive set.
#include <cmath>

#include "amha_planner/lattice/motion_primitives.h"

namespace amha {
namespace lattice {

double normalizeAngle(double a) {
  const double two_pi = 2.0 * M_PI;
  a = std::fmod(a, two_pi);
  if (a < 0.0) a += two_pi;
  if (a >= two_pi) a = 0.0;  // fmod can return values that round up to 2 pi
  return a;
}

double angleDistance(double a, double b) {
  const double d = normalizeAngle(a - b);
  return d > M_PI ? 2.0 * M_PI - d : d;
}

int PrimitiveSet::headingIndex(double theta) const {
  if (num_headings <= 0) return 0;
  if (uniform) {
    const double bin = 2.0 * M_PI / num_headings;
    const int i = static_cast<int>(normalizeAngle(theta + bin / 2.0) / bin);
    return i >= num_headings ? 0 : i;
  }
  int best = 0;
  double best_d = 10.0;
  for (int i = 0; i < num_headings; ++i) {
    const double d = angleDistance(theta, heading_angles[i]);
    if (d < best_d) {
      best_d = d;
      best = i;
    }
  }
  return best;
}

std::pair<std::size_t, std::size_t> PrimitiveSet::range(int heading) const {
  // Primitives are grouped by heading; a binary search keeps this cheap and order-agnostic.
  std::size_t lo = 0, hi = primitives.size();
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (primitives[mid].start_heading < heading)
      lo = mid + 1;
    else
      hi = mid;
  }
  std::size_t end = lo;
  while (end < primitives.size() && primitives[end].start_heading == heading) ++end;
  return {lo, end};
}

}  // namespace lattice
}  // namespace amha
