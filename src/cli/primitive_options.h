// Command-line options that choose the motion primitives beyond the first ones (--turning-radius,
// --headings, --reverse, --no-turn-in-place in lattice_options.h): the generator, the motion
// model and the reverse penalty. Shared by `amha plan`, `amha bench ...` and `amha primitives`.
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "amha_planner/lattice/lattice_planner.h"

namespace amha {
namespace cli {

struct PrimitiveOptions {
  std::optional<std::string> generator;     // "near-minimal" | "legacy"
  std::optional<std::string> motion_model;  // "diff" | "ackermann" | "omni"
  std::optional<double> reverse_penalty;    // > 0

  void addTo(CLI::App& app);
  /// Sets config's generator, motion model and reverse multiplier from what was given. With a
  /// primitive file (config.mprim_file), the generator and the motion model are refused, and so
  /// are --reverse and --reverse-penalty unless it is a Nav2 file. Throws std::invalid_argument
  /// naming the option and the value.
  void applyTo(lattice::LatticeConfig& config) const;
};

}  // namespace cli
}  // namespace amha
