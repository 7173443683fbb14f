// Fuzzes the SBPL .mprim reader: any input is either refused with a LatticeError (kPrimitives)
// naming the file and line, or gives a set that satisfies the reader's documented guarantees,
// writes out and reads back with the same structure, and (if small) builds a lattice planner
// on a small map that plans a short query without crashing.
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>

#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/lattice/motion_primitives.h"
#include "fuzz_support.h"

using namespace amha;
using namespace amha::lattice;
using amha::fuzz::finding;

namespace {

void checkSet(const PrimitiveSet& set) {
  const int n = set.num_headings;
  if (n < 1 || n > 1024) finding("num_headings out of range");
  if (!(set.resolution > 0.0) || !std::isfinite(set.resolution)) finding("resolution not positive");
  if (static_cast<int>(set.heading_angles.size()) != n) finding("heading_angles size");
  if (set.primitives.empty() || set.primitives.size() % n != 0) finding("primitive count");
  for (std::size_t i = 0; i < set.primitives.size(); ++i) {
    const MotionPrimitive& p = set.primitives[i];
    if (i > 0 && p.start_heading < set.primitives[i - 1].start_heading) finding("not grouped by heading");
    if (p.start_heading < 0 || p.start_heading >= n || p.end_heading < 0 || p.end_heading >= n) finding("heading index");
    if (!(p.cost_multiplier > 0.0)) finding("cost multiplier");
    if (p.poses.empty()) finding("no poses");
    for (const Pose2D& q : p.poses) {
      if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.theta)) finding("pose not finite");
    }
  }
  for (int h = 0; h < n; ++h) {
    const auto r = set.range(h);
    if (r.second - r.first != set.primitives.size() / n) finding("range size");
  }
}

bool sameStructure(const PrimitiveSet& a, const PrimitiveSet& b) {
  if (a.num_headings != b.num_headings || a.uniform != b.uniform || a.primitives.size() != b.primitives.size()) return false;
  for (std::size_t i = 0; i < a.primitives.size(); ++i) {
    const MotionPrimitive& p = a.primitives[i];
    const MotionPrimitive& q = b.primitives[i];
    if (p.id != q.id || p.start_heading != q.start_heading || p.end_dx != q.end_dx || p.end_dy != q.end_dy ||
        p.end_heading != q.end_heading || p.poses.size() != q.poses.size()) {
      return false;
    }
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  PrimitiveSet set;
  try {
    std::istringstream in(text);
    set = readMprim(in, "fuzz.mprim");
  } catch (const LatticeError& e) {
    if (e.kind() != LatticeError::Kind::kPrimitives) finding(std::string("wrong error kind: ") + e.what());
    if (std::string(e.what()).rfind("fuzz.mprim:", 0) != 0) finding(std::string("error does not name the file: ") + e.what());
    return 0;
  }
  checkSet(set);

  // Written out, it reads back with the same structure (when its numbers survive 6 decimals).
  std::ostringstream out;
  writeMprim(out, set);
  try {
    std::istringstream back(out.str());
    if (!sameStructure(set, readMprim(back, "written.mprim"))) finding("round trip changed the structure");
  } catch (const LatticeError&) {
  }

  // A planner on a small free map with these primitives, and a short query.
  std::size_t poses = 0;
  for (const MotionPrimitive& p : set.primitives) poses += p.poses.size();
  if (set.primitives.size() > 512 || poses > 8192) return 0;
  const double res = set.resolution;
  auto map = std::make_shared<GridMap>();
  map->width = 24;
  map->height = 20;
  map->resolution = res;
  map->cost.assign(24 * 20, kFreeCost);
  for (int y = 4; y < 12; ++y) map->cost[y * 24 + 14] = kLethalCost;
  LatticeConfig config;
  config.mprim_file = fuzz::writeScratch("fuzz.mprim", data, size);
  config.robot_radius = 0.7 * res;
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
    // e.g. primitives that do not fit the robot or the map: refused, which is fine.
  }
  return 0;
}
