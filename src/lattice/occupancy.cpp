// Occupancy percentages -> costmap-style cell costs, and GridMap construction for the ROS layer.
#include <cmath>
#include <sstream>

#include "amha_planner/lattice/map_loaders.h"

namespace amha {
namespace lattice {

std::uint8_t occupancyToCost(int v, const OccupancyConversion& conversion) {
  if (v < 0) return conversion.unknown_is_free ? kFreeCost : kUnknownCost;
  if (v >= conversion.lethal_threshold || v > 100) return kLethalCost;
  if (v == 0) return kFreeCost;
  if (v == 99) return kInscribedCost;  // reached only when lethal_threshold is 100
  return static_cast<std::uint8_t>(1 + std::lround((v - 1) * 251.0 / 97.0));
}

GridMap gridMapFromOccupancy(int width, int height, double resolution, double origin_x,
                             double origin_y, double origin_yaw, const std::int8_t* data,
                             std::size_t data_size, const OccupancyConversion& conversion,
                             std::size_t max_cells) {
  auto fail = [](const std::string& what) {
    throw LatticeError(LatticeError::Kind::kMap, "occupancy grid: " + what);
  };
  if (width <= 0 || height <= 0) {
    std::ostringstream m;
    m << "size " << width << " x " << height << " is not positive";
    fail(m.str());
  }
  const std::size_t cells = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (cells > max_cells) {
    std::ostringstream m;
    m << width << " x " << height << " = " << cells << " cells exceeds the limit of " << max_cells;
    fail(m.str());
  }
  if (!(std::isfinite(resolution) && resolution > 0.0)) {
    std::ostringstream m;
    m << "resolution " << resolution << " is not positive and finite";
    fail(m.str());
  }
  if (resolution < kMinResolution || resolution > kMaxResolution) {
    std::ostringstream m;
    m << "resolution " << resolution << " m is outside [" << kMinResolution << ", "
      << kMaxResolution << "]";
    fail(m.str());
  }
  if (!std::isfinite(origin_x) || !std::isfinite(origin_y) || !std::isfinite(origin_yaw)) {
    fail("origin is not finite");
  }
  if (std::fabs(origin_x) > kMaxOriginMagnitude || std::fabs(origin_y) > kMaxOriginMagnitude) {
    std::ostringstream m;
    m << "origin (" << origin_x << ", " << origin_y << ") is farther than " << kMaxOriginMagnitude
      << " m";
    fail(m.str());
  }
  if (std::fabs(origin_yaw) > kMaxOriginYaw) {
    std::ostringstream m;
    m << "origin yaw " << origin_yaw << " rad is beyond +-" << kMaxOriginYaw << " rad";
    fail(m.str());
  }
  if (data == nullptr && data_size > 0) fail("null data");
  if (data_size != cells) {
    std::ostringstream m;
    m << "data has " << data_size << " values, width x height is " << cells;
    fail(m.str());
  }
  if (conversion.lethal_threshold < 1 || conversion.lethal_threshold > 100) {
    std::ostringstream m;
    m << "lethal_threshold " << conversion.lethal_threshold << " outside 1..100";
    fail(m.str());
  }
  GridMap map;
  map.width = width;
  map.height = height;
  map.resolution = resolution;
  map.origin_x = origin_x;
  map.origin_y = origin_y;
  map.origin_yaw = origin_yaw;
  map.cost.resize(cells);
  std::uint8_t table[256];
  for (int v = -128; v < 128; ++v)
    table[static_cast<std::uint8_t>(v)] = occupancyToCost(v, conversion);
  for (std::size_t i = 0; i < cells; ++i) map.cost[i] = table[static_cast<std::uint8_t>(data[i])];
  return map;
}

}  // namespace lattice
}  // namespace amha
