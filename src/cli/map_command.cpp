// `amha map random`: writes a seeded random obstacle map (map_server YAML + PGM) for benchmarks.
#include <cstdio>
#include <iostream>

#include <CLI/CLI.hpp>

#include "command_registry.h"
#include "exit_codes.h"
#include "random_map.h"

namespace amha {
namespace cli {

namespace {

int mapMain(int argc, char** argv) {
  CLI::App app("Map tools.", argv[0]);
  app.require_subcommand(1);
  CLI::App* random = app.add_subcommand("random",
                                        "a seeded random obstacle map (walls, boxes, blobs of 0.2 "
                                        "- 2 m; pockets of free space filled), "
                                        "written as map_server YAML + PGM");
  RandomMapOptions o;
  std::string out;
  random->add_option("--width", o.width, "cells (default 2000)");
  random->add_option("--height", o.height, "cells (default 2000)");
  random->add_option("--resolution", o.resolution, "metres per cell (default 0.05)");
  random->add_option("--obstacles", o.obstacle_fraction,
                     "fraction of occupied cells, 0 .. 0.9 (default 0.15)");
  random->add_option("--seed", o.seed, "random seed (default 1); the same seed gives the same map");
  random->add_option("--out", out, "output DIR/name: writes DIR/name.yaml and DIR/name.pgm")
      ->required();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitUsage;
  }
  if (out.size() > 5 && out.compare(out.size() - 5, 5, ".yaml") == 0) out.resize(out.size() - 5);
  RandomMap map;
  try {
    map = randomObstacleMap(o);
  } catch (const std::invalid_argument& e) {
    std::cerr << "amha map random: " << e.what() << "\n";
    return kExitUsage;
  }
  try {
    writeMapServerFiles(out, map.occupied, o.resolution);
  } catch (const std::exception& e) {
    std::cerr << "amha map random: " << e.what() << "\n";
    return kExitOutput;
  }
  std::printf(
      "wrote %s.yaml and %s.pgm: %d x %d cells of %g m, seed %u, %d obstacles, %.2f %% occupied "
      "(%ld cells of enclosed free pockets filled)\n",
      out.c_str(), out.c_str(), o.width, o.height, o.resolution, o.seed, map.obstacles,
      100.0 * map.occupied_fraction, map.pocket_cells);
  return kExitOk;
}

}  // namespace

AMHA_REGISTER_COMMAND("map", "map tools: `amha map random` writes a seeded random obstacle map",
                      mapMain);

}  // namespace cli
}  // namespace amha
