// Readers for the map formats other planners use, all producing a GridMap with costmap-style
// cell costs (0 free .. 252, 253 inscribed, 254 lethal, 255 unknown). ROS-free.
// Every reader throws LatticeError (kMap) with a message naming the file, line and problem.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "amha_planner/lattice/lattice_config.h"

namespace amha {
namespace lattice {

/// Occupancy (nav_msgs/OccupancyGrid values) -> cell cost, as gridMapFromOccupancy does it:
///  -1 (and any value < -1): unknown -> kUnknownCost, or kFreeCost if unknown_is_free;
///  >= lethal_threshold (and any value > 100): kLethalCost;
///  99 (when lethal_threshold > 99): kInscribedCost (costmap_2d publishes 253 as 99);
///  0: kFreeCost; 1..98: 1 + round((v - 1) x 251 / 97), the inverse of costmap_2d's
///  cost_translation_table, so a published costmap comes back with its own costs.
std::uint8_t occupancyToCost(int occupancy, const OccupancyConversion& conversion);

// ---------------------------------------------------------------------------------------------
// map_server YAML + image.

enum class MapServerMode { kTrinary, kScale, kRaw };

/// What a map_server YAML file says, after validation (image path resolved against the YAML's
/// directory, as map_server does).
struct MapServerYaml {
  std::string image;  ///< absolute or relative to the current directory
  double resolution = 0.0;
  double origin[3] = {0.0, 0.0, 0.0};
  bool negate = false;
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
  MapServerMode mode = MapServerMode::kTrinary;
};

/// Parses and validates a map_server YAML file (yaml-cpp). image, resolution, origin, negate,
/// occupied_thresh and free_thresh are required as in map_server; mode is optional.
MapServerYaml readMapServerYaml(const std::string& yaml_path);

/// Occupancy values exactly as map_server publishes them (row-major, row 0 at the bottom),
/// from an 8-bit (or 16-bit, scaled to 8) grey, RGB or RGBA image read with OpenCV:
/// the mean of the channels (alpha included in trinary mode, as map_server does), negated if
/// asked, occ = (255 - mean) / 255, occ > occupied_thresh -> 100, occ < free_thresh -> 0,
/// otherwise -1 (trinary, or a transparent pixel) or 1 + 98 x ratio (scale); raw mode publishes
/// the mean itself (as a signed byte, so 255 reads as -1).
std::vector<std::int8_t> mapServerOccupancy(const MapServerYaml& yaml, int* width, int* height);

/// map_server YAML + image -> GridMap (occupancy -> cost with `conversion`; raw-mode values
/// 101..254 are lethal).
GridMap loadMapServerMap(const std::string& yaml_path,
                         const OccupancyConversion& conversion = OccupancyConversion());

// ---------------------------------------------------------------------------------------------
// Moving AI benchmark maps (.map).

/// Reads a Moving AI .map file: '.', 'G' and 'S' are free, '@', 'O', 'T', 'W' blocked (lethal).
/// Each character becomes upscale x upscale cells of `resolution` metres; the file's top row
/// becomes the top of the map (row 0 of the GridMap is the file's last row). Origin (0, 0, 0).
GridMap loadMovingAiMap(const std::string& path, double resolution, int upscale = 1);

// ---------------------------------------------------------------------------------------------
// SBPL (x, y, theta) environment files (.cfg).

struct SbplEnvironment {
  GridMap map;              ///< costs remapped to the costmap scale (see loadSbplEnvironment)
  int num_theta_dirs = 16;  ///< NumThetaDirs (16 if absent)
  int obsthresh = 254;      ///< the file's thresholds, as written
  int cost_inscribed_thresh = 253;
  int cost_possibly_circumscribed_thresh = -1;
  double nominal_speed = 1.0;    ///< nominalvel(mpersecs)
  double time_to_turn_45 = 0.0;  ///< timetoturn45degsinplace(secs)
  Pose2D start, goal;            ///< start(meters,rads) and end(meters,rads)
};

/// Reads an SBPL .cfg environment. Cell costs c become: c >= obsthresh -> kLethalCost,
/// c >= cost_inscribed_thresh -> kInscribedCost, else min(c, 252): with SBPL's usual
/// thresholds (254 / 253) the costs are unchanged. Row 0 of the file is y = 0.
SbplEnvironment loadSbplEnvironment(const std::string& path);

/// Sets `config`'s cost model to SBPL's for this environment: cost = time x multiplier x
/// (cell cost + 1) (cost_penalty 252), at the file's speed and turn-in-place time.
void useSbplCostModel(const SbplEnvironment& env, LatticeConfig& config);

/// Loads a map by extension: ".yaml"/".yml" (map_server), ".map" (Moving AI, needs
/// resolution > 0), ".cfg" (SBPL; `env` receives the whole environment if not null).
GridMap loadMapFile(const std::string& path, double movingai_resolution, int movingai_upscale,
                    const OccupancyConversion& conversion, SbplEnvironment* env = nullptr);

}  // namespace lattice
}  // namespace amha
