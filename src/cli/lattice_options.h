// Command-line options shared by `amha plan` and `amha bench lattice`: the map, the robot and
// its motion model, turned into a GridMap and a LatticeConfig. An option not given is empty
// (std::nullopt) and the library's default applies; a value given is used or refused, never
// replaced by a default.
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
  std::optional<double> resolution;  // Moving AI maps only (default 0.1)
  std::optional<int> upscale;        // Moving AI maps only (default 1)
  bool unknown_free = false;
  std::optional<int>
      lethal_threshold;  // map_server maps (.yaml) only: occupancy >= this is lethal (65)
  std::optional<std::string> mprim;
  std::optional<double> turning_radius;
  std::optional<int> headings;
  bool reverse = false;
  bool no_turn_in_place = false;
  std::optional<std::string> footprint;
  std::optional<double> radius;
  std::optional<double> cost_penalty, nominal_speed, turn_time_45;
  std::optional<int> inadmissible;
  std::string anchor = "coarse";
  std::optional<int> coarse_block;
  std::optional<double> kinematic_radius;
  std::optional<int> anchor_connectivity;
  std::optional<std::string> inadmissible_kind;
  bool backward = false;
  bool inflate_heading_terms = false;
  bool displacement_grid = false;
  double bidirectional_after = -1.0;  // --bidirectional-after; negative: off
  bool turn_term = false;      // --no-turn-term, kept for old scripts, only restates the default
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
/// robot) or std::invalid_argument (contradictory, malformed or out-of-range options, naming
/// the option and the value).
LoadedLattice loadLattice(const LatticeOptions& o);

/// "x,y,theta" -> pose; throws std::invalid_argument naming `what`.
lattice::Pose2D parsePose(const std::string& text, const char* what);

/// Exit code for a LatticeError.
int exitCodeFor(const lattice::LatticeError& e);

}  // namespace cli
}  // namespace amha
