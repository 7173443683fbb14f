// Command-line options shared by `amha plan` and `amha bench lattice`: the map, the robot and
// its motion model, turned into a GridMap and a LatticeConfig.
#pragma once

#include <limits>
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/lattice/map_loaders.h"
#include "primitive_options.h"

namespace amha {
namespace cli {

struct LatticeOptions {
  std::string map_file;
  double resolution = 0.1;  // Moving AI maps
  int upscale = 1;
  bool unknown_free = false;
  int lethal_threshold = kNotGiven;  // map_server maps: occupancy >= this is lethal (65)
  static constexpr int kNotGiven = std::numeric_limits<int>::min();
  std::string mprim;
  double turning_radius = 0.0;  // 0: not given
  int headings = 16;
  bool reverse = false;
  bool no_turn_in_place = false;
  std::string footprint;
  double radius = -1.0;  // < 0: not given
  double cost_penalty = -1.0, nominal_speed = -1.0, turn_time_45 = -1.0;  // < 0: default
  int inadmissible = 3;
  std::string anchor = "coarse";
  int coarse_block = 0;
  std::optional<double> kinematic_radius;
  int anchor_connectivity = 16;
  std::string inadmissible_kind = "kinematic";
  bool backward = false;
  bool turn_term = false;  // --no-turn-term, kept for old scripts, only restates the default
  PrimitiveOptions primitive;  // --primitive-generator, --motion-model, --reverse-penalty

  void addTo(CLI::App& app);
};

struct LoadedLattice {
  std::shared_ptr<lattice::GridMap> map;
  bool is_sbpl_env = false;
  lattice::SbplEnvironment env;  // when is_sbpl_env
  lattice::LatticeConfig config;
};

/// Loads the map and builds the configuration. Throws LatticeError (bad map, primitives or
/// robot) or std::invalid_argument (contradictory or malformed options).
LoadedLattice loadLattice(const LatticeOptions& o);

/// "x,y,theta" -> pose; throws std::invalid_argument naming `what`.
lattice::Pose2D parsePose(const std::string& text, const char* what);

/// Exit code for a LatticeError.
int exitCodeFor(const lattice::LatticeError& e);

}  // namespace cli
}  // namespace amha
