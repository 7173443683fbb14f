// PNG picture of a lattice plan: the map, every improved path (later ones brighter) and the
// robot's footprint along the last one.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "amha_planner/lattice/lattice_planner.h"

namespace amha {
namespace cli {

using FootprintFn = std::function<std::vector<std::array<double, 2>>(const lattice::Pose2D&)>;

/// Throws std::runtime_error if the file cannot be written.
void writePlanImage(const std::string& png_path, const lattice::GridMap& map,
                    const std::vector<std::vector<lattice::Pose2D>>& paths, const FootprintFn& footprint_at,
                    const lattice::Pose2D& start, const lattice::Pose2D& goal);

struct ColouredPath {
  std::vector<lattice::Pose2D> poses;
  std::array<double, 3> bgr;  ///< colour, 0..255 (blue, green, red)
};

/// The part of the map around the paths (plus `margin` metres), at most about `max_side` pixels
/// wide or high (whole cells, up to 16 pixels each), each path drawn over it in its colour, in
/// order. Throws std::runtime_error if there is no pose or the file cannot be written.
void writePathsImage(const std::string& png_path, const lattice::GridMap& map, const std::vector<ColouredPath>& paths,
                     double margin, int max_side);

}  // namespace cli
}  // namespace amha
