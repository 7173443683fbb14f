// Seeded random obstacle maps for benchmarks (`amha map random`): walls, boxes and blobs of
// 0.2 - 2 m, and rows of walls with gaps (corridors), dropped until a given fraction of the
// cells is occupied; the free pockets this closes off are filled, so the free space is one
// 4-connected region.
#pragma once

#include <string>

#include <opencv2/core/mat.hpp>

namespace amha {
namespace cli {

struct RandomMapOptions {
  int width = 2000, height = 2000;  ///< cells
  double resolution = 0.05;         ///< metres per cell
  double obstacle_fraction = 0.15;  ///< occupied cells / all cells before pockets are filled
  unsigned seed = 1;
};

struct RandomMap {
  cv::Mat occupied;                ///< CV_8U, 255 = obstacle, 0 = free; row 0 is the map's top row
  int obstacles = 0;               ///< shapes drawn (each wall of a row counts)
  long pocket_cells = 0;           ///< free cells cut off from the largest free region, now filled
  double occupied_fraction = 0.0;  ///< after filling the pockets
};

/// The same options (seed included) give the same map on every machine: the shapes come from
/// std::mt19937's raw output, not from the library's distributions. Throws
/// std::invalid_argument for sizes that are not positive (or above 2^26 cells), a resolution
/// that is not finite and positive, or a fraction outside [0, 0.9].
RandomMap randomObstacleMap(const RandomMapOptions& options);

/// Writes `base`.pgm (254 free, 0 occupied) and `base`.yaml (map_server, trinary, origin 0)
/// beside it. Throws std::runtime_error naming the file that could not be written.
void writeMapServerFiles(const std::string& base, const cv::Mat& occupied, double resolution);

}  // namespace cli
}  // namespace amha
