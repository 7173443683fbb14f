// Shortest paths of bounded curvature between two poses (Dubins 1957): at most three pieces,
// each an arc of the given radius turning left or right, or a straight line. PathSmoother joins
// lattice states with them; headings are travel directions here.
#pragma once

#include <array>
#include <vector>

#include "amha_planner/lattice/map_types.h"

namespace amha {
namespace lattice {

struct DubinsPath {
  Pose2D start;
  double radius = 0.0;
  std::array<int, 3> turn{};       ///< per piece: +1 left arc, -1 right arc, 0 straight
  std::array<double, 3> length{};  ///< per piece, metres

  double totalLength() const { return length[0] + length[1] + length[2]; }
  /// The pose at arc length s from the start (s is clamped to [0, totalLength()]).
  Pose2D at(double s) const;
};

/// The shortest of the six words (LSL, RSR, LSR, RSL, RLR, LRL) from `from` to `to`; radius > 0.
/// Each candidate is checked by following it to its end, so a word that misses `to` (by more
/// than 1e-6 of the radius) is never returned. Arcs of less than 1e-9 rad count as none.
DubinsPath shortestDubinsPath(const Pose2D& from, const Pose2D& to, double radius);

/// Poses evenly spaced along `path`, at most `spacing` metres apart, both ends included (at
/// least 2); `out` is overwritten.
void sampleDubinsPath(const DubinsPath& path, double spacing, std::vector<Pose2D>& out);

}  // namespace lattice
}  // namespace amha
