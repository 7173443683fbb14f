#include "lattice_options.h"

#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "exit_codes.h"

namespace amha {
namespace cli {

using lattice::LatticeError;

void LatticeOptions::addTo(CLI::App& app) {
  app.add_option("--map", map_file, "map file: .yaml (map_server), .map (Moving AI), .cfg (SBPL)")
      ->required();
  app.add_option("--resolution", resolution, "metres per cell of a Moving AI map (default 0.1)");
  app.add_option("--upscale", upscale, "cells per Moving AI map character, per side (default 1)");
  app.add_flag("--unknown-free", unknown_free, "treat unknown cells of map_server maps as free");
  app.add_option("--lethal-threshold", lethal_threshold,
                 "map_server maps: occupancy >= this (1..100) is an obstacle, as the server's "
                 "~lethal_threshold "
                 "(default 65, map_server's occupied_thresh); 100 reads a costmap_2d costmap saved "
                 "in raw mode: "
                 "100 lethal, 99 inscribed, 1..98 graded costs");
  app.add_option(
      "--mprim", mprim,
      "motion primitives: SBPL .mprim or Nav2 lattice .json file (default: generate them)");
  app.add_option("--turning-radius", turning_radius,
                 "generated primitives: minimum turning radius in m (default 0.5)");
  app.add_option("--headings", headings,
                 "generated primitives: headings, a multiple of 8 (default 16)");
  app.add_flag("--reverse", reverse,
               "allow backward motion (generated primitives, Nav2 .json files)");
  app.add_flag("--no-turn-in-place", no_turn_in_place,
               "generated primitives: no turns on the spot");
  primitive.addTo(app);
  app.add_option("--footprint", footprint, "robot polygon \"x,y;x,y;...\" in metres (base frame)");
  app.add_option("--radius", radius, "round robot radius in m (default 0.2; 0 = point robot)");
  app.add_option("--cost-penalty", cost_penalty,
                 "edge cost factor 1 + P x cell cost / 252 (default 1; 252 for .cfg maps = SBPL's "
                 "cost x (c+1))");
  app.add_option("--nominal-speed", nominal_speed,
                 "m/s, for costing turns (default 0.4; .cfg: the file's)");
  app.add_option("--turn-time-45", turn_time_45,
                 "seconds to turn 45 degrees in place (default 0.6; .cfg: the file's)");
  app.add_option("--inadmissible", inadmissible,
                 "number of inadmissible heuristics 0..3 (default 3)");
  app.add_option("--anchor", anchor,
                 "admissible anchor heuristic: euclidean (the paper's) | grid (+ a grid "
                 "relaxation, 8- or 16-connected: --anchor-connectivity) | coarse (+ a block "
                 "abstraction of the lattice; default)");
  app.add_option("--coarse-block", coarse_block,
                 "cells per block side of the coarse anchor (default 0 = automatic)");
  app.add_option(
      "--kinematic-radius", kinematic_radius,
      "metres: the anchor's obstacle-free kinematic cost-to-go table covers this radius around "
      "the goal (0: no table; default 10)");
  app.add_option("--anchor-connectivity", anchor_connectivity,
                 "moves of the anchor's grid: 8 or 16 (default 16)")
      ->check(CLI::IsMember({8, 16}));
  app.add_option("--inadmissible-heuristics", inadmissible_kind,
                 "kinematic (each the larger of its Dijkstra and the kinematic table; default) or "
                 "paper (the "
                 "paper's 8-connected Dijkstras alone)")
      ->check(CLI::IsMember({"kinematic", "paper"}));
  app.add_flag("--displacement-grid", displacement_grid,
               "add to the anchor the displacement grid (a 2-D cost-to-go over the primitives' "
               "own moves, computed alongside the search from its first path): faster long "
               "proofs, slower short ones");
  app.add_option("--bidirectional-after", bidirectional_after,
                 "seconds into a search after which a backward search from the goal, on a "
                 "second core, raises its anchor as it goes (a bidirectional proof): much "
                 "sooner proofs where paths turn in little room (default: off)")
      ->check(CLI::Range(0.0, 3600.0));
  auto* with_turn = app.add_flag(
      "--turn-term", turn_term,
      "add to the anchor a turning term (cost of turning to the goal's heading); off by default: "
      "many more expansions on large maps where turns are cheap");
  // Both together would silently mean one of them: refuse the pair.
  app.add_flag("--no-turn-term", "no turning term (the default; kept for old scripts)")
      ->excludes(with_turn);
  app.add_flag("--inflate-heading-terms", inflate_heading_terms,
               "let the weight inflate the heuristics' heading-aware terms too (the paper's keys g "
               "+ w h); by "
               "default it inflates only their heading-blind part, and the block abstraction, "
               "kinematic table "
               "and turning terms count once");
  app.add_flag("--backward", backward,
               "search from the goal back to the start (as SBPL does by default)");
}

lattice::Pose2D parsePose(const std::string& text, const char* what) {
  std::istringstream in(text);
  lattice::Pose2D p;
  char c1 = 0, c2 = 0;
  if (!(in >> p.x >> c1 >> p.y >> c2 >> p.theta) || c1 != ',' || c2 != ',' ||
      !(in >> std::ws).eof()) {
    throw std::invalid_argument(std::string(what) + " '" + text + "' is not x,y,theta");
  }
  return p;
}

namespace {

std::vector<std::array<double, 2>> parseFootprint(const std::string& text) {
  std::vector<std::array<double, 2>> poly;
  std::istringstream in(text);
  std::string point;
  while (std::getline(in, point, ';')) {
    if (point.find_first_not_of(" \t") == std::string::npos) continue;
    std::istringstream ps(point);
    double x = 0, y = 0;
    char comma = 0;
    if (!(ps >> x >> comma >> y) || comma != ',' || !(ps >> std::ws).eof()) {
      throw std::invalid_argument("--footprint point '" + point + "' is not x,y");
    }
    poly.push_back({x, y});
  }
  return poly;
}

}  // namespace

namespace {

bool endsWith(const std::string& s, const char* suffix) {
  const std::size_t n = std::char_traits<char>::length(suffix);
  return s.size() >= n && s.compare(s.size() - n, n, suffix) == 0;
}

bool positive(double v) { return v > 0.0 && std::isfinite(v); }
bool nonNegative(double v) { return v >= 0.0 && std::isfinite(v); }

// A given number must satisfy `ok` (NaN fails every comparison, so the checks below refuse it).
template <class T, class Ok>
void require(const std::optional<T>& v, Ok ok, const char* option, const char* expected) {
  if (!v || ok(*v)) return;
  std::ostringstream m;
  m << option << " " << *v << ": expected " << expected;
  throw std::invalid_argument(m.str());
}

}  // namespace

LoadedLattice loadLattice(const LatticeOptions& o) {
  // Every given value is checked before the map is read: a bad option is a usage error.
  const bool movingai = endsWith(o.map_file, ".map");
  if (!movingai && (o.resolution || o.upscale)) {
    throw std::invalid_argument("--resolution and --upscale apply to Moving AI maps (.map) only; " +
                                o.map_file + " has its own resolution");
  }
  const bool map_server = endsWith(o.map_file, ".yaml") || endsWith(o.map_file, ".yml");
  if (o.unknown_free && !map_server)
    throw std::invalid_argument("--unknown-free applies to map_server maps (.yaml) only");
  if (o.lethal_threshold && !map_server) {
    throw std::invalid_argument(
        "--lethal-threshold applies to map_server .yaml maps (occupancy values); " + o.map_file +
        " has cell costs of its own");
  }
  if (o.lethal_threshold && (*o.lethal_threshold < 1 || *o.lethal_threshold > 100)) {
    throw std::invalid_argument("--lethal-threshold " + std::to_string(*o.lethal_threshold) +
                                " is not in 1..100");
  }
  require(o.resolution, positive, "--resolution", "a positive number of metres");
  if (o.mprim && o.mprim->empty()) {
    throw std::invalid_argument(
        "--mprim is empty: give an SBPL .mprim or a Nav2 lattice .json file");
  }
  // --reverse stays allowed: Nav2's .json files have no backward motions of their own
  // (PrimitiveOptions::applyTo refuses it with a .mprim file).
  if (o.mprim && (o.turning_radius || o.headings || o.no_turn_in_place)) {
    throw std::invalid_argument(
        "--mprim cannot be combined with the generator options (--turning-radius, --headings, "
        "--no-turn-in-place): the file defines the primitives");
  }
  require(o.turning_radius, positive, "--turning-radius", "a positive number of metres");
  if (o.footprint && o.radius)
    throw std::invalid_argument("give --footprint or --radius, not both");
  if (o.footprint && o.footprint->find_first_not_of(" \t;") == std::string::npos) {
    throw std::invalid_argument(
        "--footprint is empty: give a polygon \"x,y;x,y;x,y;...\" of at least 3 points");
  }
  require(o.radius, nonNegative, "--radius", "a number of metres >= 0 (0: a point robot)");
  require(o.cost_penalty, nonNegative, "--cost-penalty", "a number >= 0");
  require(o.nominal_speed, positive, "--nominal-speed", "a positive speed in m/s");
  require(o.turn_time_45, nonNegative, "--turn-time-45", "a number of seconds >= 0");
  require(
      o.inadmissible, [](int k) { return k >= 0 && k <= 3; }, "--inadmissible", "0, 1, 2 or 3");
  if (o.anchor != "euclidean" && o.anchor != "grid" && o.anchor != "coarse") {
    throw std::invalid_argument("--anchor must be euclidean, grid or coarse, not '" + o.anchor +
                                "'");
  }
  if (o.coarse_block && o.anchor != "coarse")
    throw std::invalid_argument("--coarse-block applies to --anchor coarse only");
  require(
      o.coarse_block, [](int k) { return k >= 0 && k <= lattice::kMaxCoarseBlock; },
      "--coarse-block", "cells per block side in 0..1024 (0: automatic)");
  require(o.kinematic_radius, nonNegative, "--kinematic-radius",
          "a number of metres >= 0 (0: no table)");

  LoadedLattice out;
  lattice::OccupancyConversion conv;
  conv.unknown_is_free = o.unknown_free;
  if (o.lethal_threshold) conv.lethal_threshold = *o.lethal_threshold;
  out.map = std::make_shared<lattice::GridMap>(lattice::loadMapFile(
      o.map_file, o.resolution.value_or(0.1), o.upscale.value_or(1), conv, &out.env));
  out.is_sbpl_env = endsWith(o.map_file, ".cfg");

  lattice::LatticeConfig& c = out.config;
  if (o.mprim) c.motion.mprim_file = *o.mprim;
  if (o.turning_radius) c.motion.turning_radius = *o.turning_radius;
  if (o.headings) c.motion.num_headings = *o.headings;
  c.motion.allow_reverse = o.reverse;
  c.motion.turn_in_place = !o.no_turn_in_place;
  o.primitive.applyTo(c);
  if (o.footprint) c.robot.footprint = parseFootprint(*o.footprint);
  if (o.radius) c.robot.radius = *o.radius;
  if (out.is_sbpl_env) lattice::useSbplCostModel(out.env, c);
  if (o.cost_penalty) c.cost.penalty = *o.cost_penalty;
  if (o.nominal_speed) c.cost.nominal_speed = *o.nominal_speed;
  if (o.turn_time_45) c.cost.time_to_turn_45 = *o.turn_time_45;
  if (o.inadmissible) c.heuristics.num_inadmissible = *o.inadmissible;
  c.heuristics.grid_anchor = o.anchor != "euclidean";
  c.heuristics.coarse_anchor = o.anchor == "coarse";
  if (o.coarse_block) c.heuristics.coarse_block = *o.coarse_block;
  if (o.kinematic_radius) c.heuristics.kinematic_radius = *o.kinematic_radius;
  if (o.anchor_connectivity) c.heuristics.anchor_connectivity = *o.anchor_connectivity;
  // CLI::IsMember has already refused anything else.
  if (o.inadmissible_kind)
    lattice::parseInadmissible(*o.inadmissible_kind, &c.heuristics.inadmissible);
  c.heuristics.anchor_turn_term =
      o.turn_term;  // --no-turn-term is the default (the two exclude each other)
  c.heuristics.inflate_heading_terms = o.inflate_heading_terms;
  c.heuristics.displacement_grid = o.displacement_grid;
  c.heuristics.bidirectional_after_s = o.bidirectional_after;
  c.backward_search = o.backward;
  return out;
}

int exitCodeFor(const LatticeError& e) {
  switch (e.kind()) {
    case LatticeError::Kind::kMap:
      return kExitBadMap;
    case LatticeError::Kind::kPrimitives:
      return kExitBadPrimitives;
    case LatticeError::Kind::kRobot:
    case LatticeError::Kind::kConfig:
      return kExitUsage;
  }
  return kExitInternal;
}

}  // namespace cli
}  // namespace amha
