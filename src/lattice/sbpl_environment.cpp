// SBPL (x, y, theta) environment files (.cfg), read token by token as SBPL does, but with
// errors that name the line; plus loading any map by its extension.
#include <fstream>
#include <sstream>

#include "amha_planner/lattice/map_loaders.h"
#include "tokenizer.h"

namespace amha {
namespace lattice {

SbplEnvironment loadSbplEnvironment(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw LatticeError(LatticeError::Kind::kMap, file + ": cannot open the file");
  detail::Tokenizer t(in, file, LatticeError::Kind::kMap);
  SbplEnvironment env;
  GridMap& map = env.map;

  t.expect("discretization(cells):");
  const long w = t.integer("the width in cells");
  const long h = t.integer("the height in cells");
  if (w <= 0 || h <= 0 || w > 1000000 || h > 1000000 ||
      static_cast<std::size_t>(w) * static_cast<std::size_t>(h) > (std::size_t{1} << 26)) {
    t.fail("map size " + std::to_string(w) + " x " + std::to_string(h) +
           " is not positive or exceeds 2^26 cells");
  }
  std::string label = t.next();
  if (label == "NumThetaDirs:") {
    const long n = t.integer("NumThetaDirs");
    if (n < 1 || n > 1024) t.fail("NumThetaDirs " + std::to_string(n) + " is not in 1..1024");
    env.num_theta_dirs = static_cast<int>(n);
    label = t.next();
  }
  if (label != "obsthresh:") t.fail("expected 'obsthresh:' but found '" + label + "'");
  auto threshold = [&](const char* what) {
    const long v = t.integer(what);
    if (v < -1 || v > 255)
      t.fail(std::string(what) + " " + std::to_string(v) + " is not in -1..255");
    return static_cast<int>(v);
  };
  env.obsthresh = threshold("obsthresh");
  if (env.obsthresh < 1) t.fail("obsthresh must be at least 1");
  t.expect("cost_inscribed_thresh:");
  env.cost_inscribed_thresh = threshold("cost_inscribed_thresh");
  t.expect("cost_possibly_circumscribed_thresh:");
  env.cost_possibly_circumscribed_thresh = threshold("cost_possibly_circumscribed_thresh");
  t.expect("cellsize(meters):");
  map.resolution = t.number("the cell size");
  if (!(map.resolution > 0.0)) t.fail("cell size must be positive");
  t.expect("nominalvel(mpersecs):");
  env.nominal_speed = t.number("the nominal velocity");
  if (!(env.nominal_speed > 0.0)) t.fail("nominal velocity must be positive");
  t.expect("timetoturn45degsinplace(secs):");
  env.time_to_turn_45 = t.number("the time to turn 45 degrees");
  if (env.time_to_turn_45 < 0.0) t.fail("time to turn 45 degrees must not be negative");
  t.expect("start(meters,rads):");
  env.start.x = t.number("start x");
  env.start.y = t.number("start y");
  env.start.theta = t.number("start theta");
  t.expect("end(meters,rads):");
  env.goal.x = t.number("end x");
  env.goal.y = t.number("end y");
  env.goal.theta = t.number("end theta");
  t.expect("environment:");

  map.width = static_cast<int>(w);
  map.height = static_cast<int>(h);
  map.cost.resize(static_cast<std::size_t>(w) * h);
  const int inscribed = env.cost_inscribed_thresh;
  for (long y = 0; y < h; ++y) {
    for (long x = 0; x < w; ++x) {
      const std::string tok = t.next();
      if (tok.empty()) {
        t.fail("the environment ends at cell (" + std::to_string(x) + ", " + std::to_string(y) +
               "); expected " + std::to_string(w) + " x " + std::to_string(h) + " costs");
      }
      char* end = nullptr;
      const long c = std::strtol(tok.c_str(), &end, 10);
      if (end == tok.c_str() || *end != '\0' || c < 0 || c > 255) {
        t.fail("cell (" + std::to_string(x) + ", " + std::to_string(y) + "): cost '" + tok +
               "' is not an integer in 0..255");
      }
      std::uint8_t cost;
      if (c >= env.obsthresh) {
        cost = kLethalCost;
      } else if (inscribed >= 0 && c >= inscribed) {
        cost = kInscribedCost;
      } else {
        cost = static_cast<std::uint8_t>(std::min<long>(c, 252));
      }
      map.cost[static_cast<std::size_t>(y) * w + x] = cost;
    }
  }
  const std::string extra = t.next();
  if (!extra.empty())
    t.fail("unexpected '" + extra + "' after the " + std::to_string(w) + " x " + std::to_string(h) +
           " costs");
  return env;
}

namespace {
bool endsWith(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  std::string tail = s.substr(s.size() - suffix.size());
  for (auto& c : tail) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return tail == suffix;
}
}  // namespace

GridMap loadMapFile(const std::string& path, double movingai_resolution, int movingai_upscale,
                    const OccupancyConversion& conversion, SbplEnvironment* env) {
  if (endsWith(path, ".yaml") || endsWith(path, ".yml")) return loadMapServerMap(path, conversion);
  if (endsWith(path, ".map")) return loadMovingAiMap(path, movingai_resolution, movingai_upscale);
  if (endsWith(path, ".cfg")) {
    SbplEnvironment e = loadSbplEnvironment(path);
    GridMap m = std::move(e.map);  // one copy of the cells: env keeps the header only
    if (env != nullptr) *env = std::move(e);
    return m;
  }
  throw LatticeError(LatticeError::Kind::kMap,
                     path + ": unknown map format (expected .yaml, .map or .cfg)");
}

void useSbplCostModel(const SbplEnvironment& env, LatticeConfig& config) {
  config.cost.penalty = 252.0;
  config.cost.nominal_speed = env.nominal_speed;
  config.cost.time_to_turn_45 = env.time_to_turn_45;
}

}  // namespace lattice
}  // namespace amha
