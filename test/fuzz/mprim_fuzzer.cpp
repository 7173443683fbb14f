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
#include "primitive_fuzz_support.h"

using namespace amha;
using namespace amha::lattice;
using amha::fuzz::finding;

namespace {

void checkSet(const PrimitiveSet& set) {
  const int n = set.num_headings;
  if (n < 1 || n > 1024) finding("num_headings out of range");
  if (!(set.resolution > 0.0) || !std::isfinite(set.resolution)) finding("resolution not positive");
  if (static_cast<int>(set.heading_angles.size()) != n) finding("heading_angles size");
  if (set.primitives.empty()) finding("primitive count");
  for (std::size_t i = 0; i < set.primitives.size(); ++i) {
    const MotionPrimitive& p = set.primitives[i];
    if (i > 0 && p.start_heading < set.primitives[i - 1].start_heading)
      finding("not grouped by heading");
    if (p.start_heading < 0 || p.start_heading >= n || p.end_heading < 0 || p.end_heading >= n)
      finding("heading index");
    if (!(p.cost_multiplier > 0.0)) finding("cost multiplier");
    if (p.poses.empty()) finding("no poses");
    for (const Pose2D& q : p.poses) {
      if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.theta))
        finding("pose not finite");
    }
  }
  // Every heading has primitives (files have the same number for each; exact copies, which
  // pad them, are dropped).
  for (int h = 0; h < n; ++h) {
    const auto r = set.range(h);
    if (r.second == r.first) finding("a heading without primitives");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  PrimitiveSet set;
  if (!fuzz::readOrRefuse(text, "fuzz.mprim", readMprim, &set)) return 0;
  checkSet(set);

  // Written out, it reads back with the same structure (when its numbers survive 6 decimals).
  fuzz::checkRoundTrip(set, writeMprim, readMprim, "written.mprim", true);

  // A planner on a small free map with these primitives, and a short query.
  fuzz::planOnSmallMap(set, fuzz::writeScratch("fuzz.mprim", data, size), false);
  return 0;
}
