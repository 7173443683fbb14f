// SBPL .mprim writer (the format readMprim reads; the non-uniform variant when needed).
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
  out << "resolution_m: " << fmt("%.6f", set.resolution) << "\n";
  if (!set.uniform) out << "min_turning_radius_m: " << fmt("%.6f", set.min_turning_radius) << "\n";
  out << "numberofangles: " << set.num_headings << "\n";
  if (!set.uniform) {
    for (int i = 0; i < set.num_headings; ++i) {
      out << "angle:" << i << " " << fmt("%.10f", set.heading_angles[i]) << "\n";
    }
  }
  out << "totalnumberofprimitives: " << set.primitives.size() << "\n";
  for (const MotionPrimitive& p : set.primitives) {
    out << "primID: " << p.id << "\n";
    out << "startangle_c: " << p.start_heading << "\n";
    out << "endpose_c: " << p.end_dx << " " << p.end_dy << " " << p.end_heading << "\n";
    const double m = p.cost_multiplier;
    // SBPL reads an integer multiplier: write integers as such (ours also reads decimals).
    out << "additionalactioncostmult: " << (m == std::floor(m) ? fmt("%.0f", m) : fmt("%.6f", m)) << "\n";
    if (!set.uniform) out << "turning_radius: " << fmt("%.6f", p.turning_radius) << "\n";
    out << "intermediateposes: " << p.poses.size() << "\n";
    for (const Pose2D& q : p.poses) {
      out << fmt("%.6f", q.x) << " " << fmt("%.6f", q.y) << " " << fmt("%.6f", normalizeAngle(q.theta)) << "\n";
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
