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
                    const std::vector<std::vector<lattice::Pose2D>>& paths,
                    const FootprintFn& footprint_at, const lattice::Pose2D& start,
                    const lattice::Pose2D& goal);

/// A path drawn in its own colour (BGR) and named in the legend.
struct LabelledPath {
  std::string label;
  std::array<int, 3> bgr;
  std::vector<lattice::Pose2D> poses;
};

/// PNG of several paths on the part of the map around them (with a margin of `margin_m`),
/// scaled up to about 900 pixels, each path in its colour, with a legend, start and goal.
/// Throws std::runtime_error if the file cannot be written.
void writePathsImage(const std::string& png_path, const lattice::GridMap& map,
                     const std::vector<LabelledPath>& paths, const lattice::Pose2D& start,
                     const lattice::Pose2D& goal, double margin_m = 2.0);

}  // namespace cli
}  // namespace amha
