// `amha primitives`: generates a primitive set (or reads one) and writes it as a Nav2 lattice
// file (.json) or an SBPL .mprim file, with a summary of what it holds.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

#include <CLI/CLI.hpp>

#include "amha_planner/lattice/motion_primitives.h"
#include "command_registry.h"
#include "exit_codes.h"
#include "lattice_options.h"
#include "primitive_options.h"

namespace amha {
namespace cli {

namespace {

void printSummary(const lattice::PrimitiveSet& s) {
  std::printf(
      "%d headings, resolution %g m, minimum turning radius %g m, motion model %s: %zu "
      "primitives\n",
      s.num_headings, s.resolution, s.min_turning_radius,
      s.motion_model.empty() ? "?" : s.motion_model.c_str(), s.primitives.size());
  std::printf("primitives per heading:");
  for (int h = 0; h < s.num_headings; ++h) {
    const auto r = s.range(h);
    std::printf(" %zu", r.second - r.first);
  }
  std::printf("\n");
  // The first octant's headings stand for all the others (the generators' sets are symmetric).
  for (int h = 0; h <= std::max(1, s.num_headings / 8) && h < s.num_headings; ++h) {
    const auto r = s.range(h);
    std::printf("heading %d (%.4f rad):\n", h, s.heading_angles[h]);
    for (std::size_t i = r.first; i < r.second; ++i) {
      const lattice::MotionPrimitive& p = s.primitives[i];
      std::printf(
          "  to (%3d, %3d) heading %2d  length %.4f m (arc %.4f, straight %.4f)  radius "
          "%7.4f%s%s\n",
          p.end_dx, p.end_dy, p.end_heading, p.arc_length + p.straight_length, p.arc_length,
          p.straight_length, p.turning_radius, p.reverse ? "  backward" : "",
          p.cost_multiplier != 1.0 ? ("  x" + std::to_string(p.cost_multiplier)).c_str() : "");
    }
  }
}

int primitivesMain(int argc, char** argv) {
  CLI::App app(
      "Generates motion primitives (or reads a file of them) and writes them as a Nav2 lattice "
      "file "
      "(.json) or an SBPL .mprim file, so that one set serves both Nav2 and this planner.",
      argv[0]);
  std::string in, out;
  lattice::PrimitiveGeneratorOptions o;
  LatticeOptions lo;  // only the generator's options are read from it
  bool quiet = false;
  app.add_option(
      "--in", in,
      "read this primitive file (.json Nav2 lattice, else .mprim) instead of generating");
  app.add_option("--out", out, "write the set here: .json (Nav2 lattice file) or .mprim (SBPL)");
  app.add_option("--resolution", o.resolution,
                 "generated primitives: metres per cell (default 0.05)");
  app.add_option("--headings", lo.headings,
                 "generated primitives: headings, a multiple of 8 (default 16)");
  app.add_option("--turning-radius", o.turning_radius,
                 "generated primitives: minimum turning radius in m (default 0.5)");
  app.add_flag("--reverse", lo.reverse, "add backward motions");
  app.add_flag("--no-turn-in-place", lo.no_turn_in_place,
               "generated primitives: no turns on the spot");
  app.add_option("--tolerance", o.tolerance,
                 "near-minimal generator: drop a candidate that shorter primitives reproduce "
                 "within (1 + this) times "
                 "its length (default 0.2)");
  app.add_option(
      "--end-tolerance", o.end_tolerance,
      "near-minimal generator: ... or reproduce a turn ending this many cells from it (default 2)");
  lo.primitive.addTo(app);
  app.add_flag("--quiet", quiet, "no summary");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitUsage;
  }
  lattice::PrimitiveSet set;
  const auto t0 = std::chrono::steady_clock::now();
  try {
    lattice::LatticeConfig c;
    c.motion.mprim_file = in;
    c.motion.allow_reverse = lo.reverse;
    lo.primitive.applyTo(c);
    if (!in.empty()) {
      if (app.count("--resolution") || app.count("--headings") || app.count("--turning-radius") ||
          app.count("--no-turn-in-place") || app.count("--tolerance") ||
          app.count("--end-tolerance")) {
        throw std::invalid_argument("--in cannot be combined with the generator options");
      }
      set = lattice::primitivesFor(c, 0.0);
    } else {
      o.num_headings = lo.headings.value_or(o.num_headings);
      o.allow_reverse = lo.reverse;
      o.turn_in_place = !lo.no_turn_in_place;
      o.generator = c.motion.generator;
      o.motion_model = c.motion.model;
      o.reverse_multiplier = c.cost.reverse_multiplier;
      set = lattice::generatePrimitives(o);
    }
  } catch (const lattice::LatticeError& e) {
    std::cerr << "amha primitives: " << e.what() << "\n";
    return exitCodeFor(e);
  } catch (const std::invalid_argument& e) {
    std::cerr << "amha primitives: " << e.what() << "\n";
    return kExitUsage;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!quiet) {
    printSummary(set);
    std::printf("%s in %.3f s\n", in.empty() ? "generated" : "read", seconds);
  }
  if (!out.empty()) {
    try {
      lattice::writePrimitiveFile(out, set);
    } catch (const lattice::LatticeError& e) {
      std::cerr << "amha primitives: " << e.what() << "\n";
      return kExitOutput;
    }
    if (!quiet) std::printf("wrote %s\n", out.c_str());
  }
  return kExitOk;
}

}  // namespace

AMHA_REGISTER_COMMAND("primitives",
                      "generate motion primitives and write them as Nav2 .json or SBPL .mprim",
                      primitivesMain);

}  // namespace cli
}  // namespace amha
