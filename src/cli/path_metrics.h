// How smooth a path is, for `amha plan --smooth` and `amha bench smooth`: length, curvature,
// heading change, curvature sign changes. Curvature is measured per step between consecutive
// poses as 2 sin(|dtheta| / 2) / |dp| (the circle through both positions, exact on an arc).
#pragma once

#include <vector>

#include "amha_planner/lattice/lattice_planner.h"

namespace amha {
namespace cli {

struct PathMetrics {
  double length = 0.0;                    ///< metres
  double mean_curvature = 0.0;            ///< 1/m, |curvature| averaged over the length driven
  double max_curvature = 0.0;             ///< 1/m, largest |curvature| while driving
  double heading_change_per_metre = 0.0;  ///< total |dtheta| (turns in place included) / length
  int curvature_sign_changes = 0;         ///< left to right turns and back, while driving (steps
                                          ///< under 1e-3 /m count as straight, not as a side)
};

/// Steps that do not move (turns in place) add heading change only.
PathMetrics pathMetrics(const std::vector<lattice::Pose2D>& poses);

}  // namespace cli
}  // namespace amha
