// SBPL .mprim writer (the format readMprim reads; the non-uniform variant when needed).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "amha_planner/lattice/motion_primitives.h"

namespace amha {
namespace lattice {

namespace {
std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}
}  // namespace

void writeMprim(std::ostream& out, const PrimitiveSet& set) {
  // SBPL indexes every heading's actions up to the largest count: pad the others with copies.
  std::size_t per = 0;
  for (int h = 0; h < set.num_headings; ++h) {
    const auto r = set.range(h);
    per = std::max(per, r.second - r.first);
  }
  out << "resolution_m: " << fmt("%.6f", set.resolution) << "\n";
  if (!set.uniform) out << "min_turning_radius_m: " << fmt("%.6f", set.min_turning_radius) << "\n";
  out << "numberofangles: " << set.num_headings << "\n";
  if (!set.uniform) {
    for (int i = 0; i < set.num_headings; ++i) {
      out << "angle:" << i << " " << fmt("%.10f", set.heading_angles[i]) << "\n";
    }
  }
  out << "totalnumberofprimitives: " << per * set.num_headings << "\n";
  for (int h = 0; h < set.num_headings; ++h) {
    const auto r = set.range(h);
    if (r.first == r.second)
      throw LatticeError(LatticeError::Kind::kPrimitives,
                         "heading " + std::to_string(h) + " has no primitives");
    int next_id = 0;
    for (std::size_t i = r.first; i < r.second; ++i)
      next_id = std::max(next_id, set.primitives[i].id + 1);
    for (std::size_t k = 0; k < per; ++k) {
      const bool copy = r.first + k >= r.second;  // padding: the first again, with a new primID
      const MotionPrimitive& p = set.primitives[copy ? r.first : r.first + k];
      out << "primID: " << (copy ? next_id++ : p.id) << "\n";
      out << "startangle_c: " << p.start_heading << "\n";
      out << "endpose_c: " << p.end_dx << " " << p.end_dy << " " << p.end_heading << "\n";
      const double m = p.cost_multiplier;
      // SBPL reads an integer multiplier: write integers as such (ours also reads decimals).
      out << "additionalactioncostmult: " << (m == std::floor(m) ? fmt("%.0f", m) : fmt("%.6f", m))
          << "\n";
      if (!set.uniform) out << "turning_radius: " << fmt("%.6f", p.turning_radius) << "\n";
      out << "intermediateposes: " << p.poses.size() << "\n";
      for (const Pose2D& q : p.poses) {
        out << fmt("%.6f", q.x) << " " << fmt("%.6f", q.y) << " "
            << fmt("%.6f", normalizeAngle(q.theta)) << "\n";
      }
    }
  }
}

void writeMprimFile(const std::string& path, const PrimitiveSet& set) {
  std::ofstream out(path);
  if (!out) throw LatticeError(LatticeError::Kind::kPrimitives, path + ": cannot write the file");
  writeMprim(out, set);
  out.flush();
  if (!out) throw LatticeError(LatticeError::Kind::kPrimitives, path + ": write failed");
}

}  // namespace lattice
}  // namespace amha
