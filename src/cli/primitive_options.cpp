#include "primitive_options.h"

#include <cmath>
#include <stdexcept>

#include "amha_planner/lattice/motion_primitives.h"

namespace amha {
namespace cli {

void PrimitiveOptions::addTo(CLI::App& app) {
  app.add_option(
      "--primitive-generator", generator,
      "generated primitives: near-minimal (a near-minimal control set, the default) | legacy (the "
      "first generator: arcs to the neighbouring headings only)");
  app.add_option("--motion-model", motion_model,
                 "generated primitives: diff (turns on the spot, the default) | ackermann (never) "
                 "| omni (turns "
                 "on the spot and slides sideways)");
  app.add_option("--reverse-penalty", reverse_penalty,
                 "cost multiplier of backward motions, > 0 (default 3; with --reverse)");
}

void PrimitiveOptions::applyTo(lattice::LatticeConfig& c) const {
  const bool file = !c.motion.mprim_file.empty();
  if (file && (generator || motion_model)) {
    throw std::invalid_argument(
        "--mprim cannot be combined with --primitive-generator or --motion-model");
  }
  if (file && !lattice::isNav2LatticePath(c.motion.mprim_file) &&
      (c.motion.allow_reverse || reverse_penalty)) {
    throw std::invalid_argument(
        "--reverse and --reverse-penalty apply to generated primitives and Nav2 files (.json), "
        "not to a .mprim file (its backward motions are in the file)");
  }
  if (generator && !lattice::parsePrimitiveGenerator(*generator, &c.motion.generator)) {
    throw std::invalid_argument("--primitive-generator must be near-minimal or legacy, not '" +
                                *generator + "'");
  }
  if (motion_model && !lattice::parseMotionModel(*motion_model, &c.motion.model)) {
    throw std::invalid_argument("--motion-model must be diff, ackermann or omni, not '" +
                                *motion_model + "'");
  }
  if (reverse_penalty) {
    if (!(*reverse_penalty > 0.0) || !std::isfinite(*reverse_penalty)) {
      throw std::invalid_argument("--reverse-penalty must be a finite number > 0, not " +
                                  std::to_string(*reverse_penalty));
    }
    if (!c.motion.allow_reverse) throw std::invalid_argument("--reverse-penalty needs --reverse");
    c.cost.reverse_multiplier = *reverse_penalty;
  }
}

}  // namespace cli
}  // namespace amha
