// Nav2 lattice primitive files (see motion_primitives.h): what Nav2's reader requires, poses
// without the start pose of a move, backward motions left to Nav2.
#include <cmath>
#include <ctime>
#include <fstream>

#include <nlohmann/json.hpp>

#include "amha_planner/lattice/motion_primitives.h"

namespace amha {
namespace lattice {

namespace {

// Micrometres are plenty and keep the file short (the JSON writer prints shortest round trips).
double rounded(double v) { return std::round(v * 1e6) / 1e6; }

std::string today() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[16];
  std::strftime(buf, sizeof buf, "%Y-%m-%d", &tm);
  return buf;
}

}  // namespace

void writeNav2Lattice(std::ostream& out, const PrimitiveSet& set) {
  using nlohmann::json;
  json prims = json::array();
  bool turns_on_the_spot = false;
  for (const MotionPrimitive& p : set.primitives) {
    if (p.reverse) continue;
    const bool in_place = p.end_dx == 0 && p.end_dy == 0;
    turns_on_the_spot |= in_place;
    json poses = json::array();
    for (std::size_t k = in_place ? 0 : 1; k < p.poses.size(); ++k) {
      const Pose2D& q = p.poses[k];
      poses.push_back({rounded(q.x), rounded(q.y), rounded(normalizeAngle(q.theta))});
    }
    prims.push_back({{"trajectory_id", prims.size()},
                     {"start_angle_index", p.start_heading},
                     {"end_angle_index", p.end_heading},
                     {"left_turn", p.turning_radius >= 0.0},
                     {"trajectory_radius", rounded(std::fabs(p.turning_radius))},
                     {"trajectory_length", rounded(p.arc_length + p.straight_length)},
                     {"arc_length", rounded(p.arc_length)},
                     {"straight_length", rounded(p.straight_length)},
                     {"poses", poses}});
  }
  json angles = json::array();
  for (double a : set.heading_angles) angles.push_back(a);
  const std::string model = !set.motion_model.empty() ? set.motion_model
                            : turns_on_the_spot       ? "diff"
                                                      : "ackermann";
  const json doc = {{"version", 1.0},
                    {"date_generated", today()},
                    {"lattice_metadata",
                     {{"motion_model", model},
                      {"turning_radius", set.min_turning_radius},
                      {"grid_resolution", set.resolution},
                      {"num_of_headings", set.num_headings},
                      {"heading_angles", angles},
                      {"number_of_trajectories", prims.size()}}},
                    {"primitives", prims}};
  out << doc.dump(1) << "\n";
}

void writeNav2LatticeFile(const std::string& path, const PrimitiveSet& set) {
  std::ofstream out(path);
  if (!out) throw LatticeError(LatticeError::Kind::kPrimitives, path + ": cannot write the file");
  writeNav2Lattice(out, set);
  out.flush();
  if (!out) throw LatticeError(LatticeError::Kind::kPrimitives, path + ": write failed");
}

}  // namespace lattice
}  // namespace amha
