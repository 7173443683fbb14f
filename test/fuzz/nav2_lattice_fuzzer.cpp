// Fuzzes the Nav2 lattice (JSON) reader: any input is either refused with a LatticeError
// (kPrimitives) naming the file, or gives a set that satisfies the reader's documented
// guarantees, writes out as JSON and as .mprim and reads back with the same structure, and (if
// small) builds a lattice planner on a small map that plans a short query without crashing.
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>

#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/lattice/motion_primitives.h"
#include "fuzz_support.h"
#include "primitive_fuzz_support.h"

using namespace amha;
using namespace amha::lattice;
using amha::fuzz::finding;

namespace {

void checkSet(const PrimitiveSet& set) {
  const int n = set.num_headings;
  if (n < 1 || n > 1024) finding("num_headings out of range");
  if (!(set.resolution >= kMinResolution && set.resolution <= kMaxResolution))
    finding("resolution out of range");
  if (static_cast<int>(set.heading_angles.size()) != n) finding("heading_angles size");
  for (int h = 0; h < n; ++h) {
    const double a = set.heading_angles[h];
    if (!(a >= 0.0 && a < 2.0 * M_PI) || (h > 0 && !(a > set.heading_angles[h - 1])))
      finding("heading angles");
    const auto r = set.range(h);
    if (r.first == r.second) finding("a heading without primitives");
  }
  for (std::size_t i = 0; i < set.primitives.size(); ++i) {
    const MotionPrimitive& p = set.primitives[i];
    if (i > 0 && p.start_heading < set.primitives[i - 1].start_heading)
      finding("not grouped by heading");
    if (p.start_heading < 0 || p.start_heading >= n || p.end_heading < 0 || p.end_heading >= n)
      finding("heading index");
    if (p.poses.empty() || p.poses.front().x != 0.0 || p.poses.front().y != 0.0)
      finding("the first pose is not the start");
    for (const Pose2D& q : p.poses) {
      if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.theta))
        finding("pose not finite");
    }
    const Pose2D& last = p.poses.back();
    if (std::fabs(last.x / set.resolution - p.end_dx) > 0.011 ||
        std::fabs(last.y / set.resolution - p.end_dy) > 0.011) {
      finding("the last pose is not at the end cell");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  PrimitiveSet set;
  if (!fuzz::readOrRefuse(text, "fuzz.json", readNav2Lattice, &set)) return 0;
  checkSet(set);

  // Written out as JSON, and as .mprim (padded to the same count per heading, the copies
  // dropped when read), it reads back with the same structure.
  fuzz::checkRoundTrip(set, writeNav2Lattice, readNav2Lattice, "written.json", false);
  fuzz::checkRoundTrip(set, writeMprim, readMprim, "written.mprim", false);

  // A planner on a small free map with these primitives (and, for odd sizes, their backward
  // twins), and a short query.
  fuzz::planOnSmallMap(set, fuzz::writeScratch("fuzz.json", data, size), (size & 1) != 0);
  return 0;
}
