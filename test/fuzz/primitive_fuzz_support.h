// Shared by the primitive file fuzzers: a planner built from the fuzzed file plans on a small map.
#pragma once

#include <cmath>
#include <memory>
#include <sstream>
#include <string>

#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/lattice/motion_primitives.h"
#include "fuzz_support.h"

namespace amha {
namespace fuzz {

using PrimitiveReader = lattice::PrimitiveSet (*)(std::istream&, const std::string&, double);

/// Reads `text` as file `name` with `read`: true with the set, or false when refused with a
/// LatticeError, which must be of kind kPrimitives and start with the file's name.
inline bool readOrRefuse(const std::string& text, const std::string& name, PrimitiveReader read,
                         lattice::PrimitiveSet* set) {
  try {
    std::istringstream in(text);
    *set = read(in, name, 0.0);
    return true;
  } catch (const lattice::LatticeError& e) {
    if (e.kind() != lattice::LatticeError::Kind::kPrimitives)
      finding(std::string("wrong error kind: ") + e.what());
    if (std::string(e.what()).rfind(name + ":", 0) != 0)
      finding(std::string("error does not name the file: ") + e.what());
    return false;
  }
}

/// The same motions in the same order: start and end states and the number of poses (and the
/// primIDs, if asked).
inline bool sameMotions(const lattice::PrimitiveSet& a, const lattice::PrimitiveSet& b, bool ids) {
  if (a.num_headings != b.num_headings || a.primitives.size() != b.primitives.size()) return false;
  for (std::size_t i = 0; i < a.primitives.size(); ++i) {
    const lattice::MotionPrimitive& p = a.primitives[i];
    const lattice::MotionPrimitive& q = b.primitives[i];
    if ((ids && p.id != q.id) || p.start_heading != q.start_heading || p.end_dx != q.end_dx ||
        p.end_dy != q.end_dy || p.end_heading != q.end_heading ||
        p.poses.size() != q.poses.size()) {
      return false;
    }
  }
  return true;
}

using PrimitiveWriter = void (*)(std::ostream&, const lattice::PrimitiveSet&);

/// Written out with `write` and read back with `read`, `set` has the same motions (or is
/// refused: rounding to 6 decimals may move a pose out of its cell).
inline void checkRoundTrip(const lattice::PrimitiveSet& set, PrimitiveWriter write,
                           PrimitiveReader read, const std::string& name, bool ids) {
  std::ostringstream out;
  write(out, set);
  try {
    std::istringstream back(out.str());
    if (!sameMotions(set, read(back, name, 0.0), ids))
      finding("written as " + name + ", it reads back different");
  } catch (const lattice::LatticeError&) {
  }
}

/// If `set` (read from `file`) is small, builds a lattice planner with the file on a 24 x 20 map
/// with a wall, and plans a short query with A* and A-MHA*: every solution must start at the
/// start and be a real path. A planner refused with a LatticeError (primitives that do not fit
/// the robot or the map, headings without opposites for backward twins) is fine.
inline void planOnSmallMap(const lattice::PrimitiveSet& set, const std::string& file,
                           bool allow_reverse) {
  using namespace amha::lattice;
  std::size_t poses = 0;
  for (const MotionPrimitive& p : set.primitives) poses += p.poses.size();
  if (set.primitives.size() > 512 || poses > 8192) return;
  const double res = set.resolution;
  auto map = std::make_shared<GridMap>();
  map->width = 24;
  map->height = 20;
  map->resolution = res;
  map->cost.assign(24 * 20, kFreeCost);
  for (int y = 4; y < 12; ++y) map->cost[y * 24 + 14] = kLethalCost;
  LatticeConfig config;
  config.motion.mprim_file = file;
  config.robot.radius = 0.7 * res;
  config.motion.allow_reverse = allow_reverse;
  try {
    LatticePlanner planner(map, config);
    const int n = set.num_headings;
    const Pose2D start{8.5 * res, 8.5 * res, set.heading_angles[0]};
    const Pose2D goal{18.5 * res, 9.5 * res, set.heading_angles[n / 2]};
    SearchLimits limits;
    limits.max_expansions = 2000;
    for (Algorithm a : {Algorithm::kAStar, Algorithm::kAmhaStar}) {
      const PlanResult r = planner.plan(start, goal, defaultConfig(a), limits);
      for (const LatticeSolution& s : r.solutions) {
        if (s.poses.empty() || std::fabs(s.poses.front().x - start.x) > 1e-6 * (1 + res) ||
            std::fabs(s.poses.front().y - start.y) > 1e-6 * (1 + res)) {
          finding("a solution does not start at the start");
        }
        if (s.search.cost < 1 || s.search.path.empty()) finding("bad solution");
      }
    }
  } catch (const LatticeError&) {
  }
}

}  // namespace fuzz
}  // namespace amha
