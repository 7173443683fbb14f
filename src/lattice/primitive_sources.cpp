// Where a lattice's primitives come from: a file of either format, or a generator; and the
// backward twins that Nav2's files leave to the planner.
#include <cmath>

#include "amha_planner/lattice/motion_primitives.h"
#include "primitive_geometry.h"

namespace amha {
namespace lattice {

PrimitiveSet generatePrimitives(const PrimitiveGeneratorOptions& o) {
  return o.generator == PrimitiveGenerator::kLegacy ? generateLegacyPrimitives(o)
                                                    : generateNearMinimalPrimitives(o);
}

PrimitiveGeneratorOptions generatorOptionsFor(const LatticeConfig& c, double resolution) {
  PrimitiveGeneratorOptions o;
  o.resolution = resolution;
  o.num_headings = c.motion.num_headings;
  o.turning_radius = c.motion.turning_radius;
  o.allow_reverse = c.motion.allow_reverse;
  o.turn_in_place = c.motion.turn_in_place;
  o.reverse_multiplier = c.cost.reverse_multiplier;
  o.generator = c.motion.generator;
  o.motion_model = c.motion.model;
  return o;
}

PrimitiveSet primitivesFor(const LatticeConfig& c, double resolution) {
  if (c.motion.mprim_file.empty()) return generatePrimitives(generatorOptionsFor(c, resolution));
  PrimitiveSet set = readPrimitiveFile(c.motion.mprim_file, resolution);
  if (c.motion.allow_reverse && isNav2LatticePath(c.motion.mprim_file)) {
    if (!(c.cost.reverse_multiplier > 0.0) || !std::isfinite(c.cost.reverse_multiplier)) {
      throw LatticeError(LatticeError::Kind::kConfig, "reverse_multiplier must be positive");
    }
    addBackwardTwins(set, c.cost.reverse_multiplier);
  }
  return set;
}

bool isNav2LatticePath(const std::string& path) {
  return path.size() >= 5 && path.compare(path.size() - 5, 5, ".json") == 0;
}

PrimitiveSet readPrimitiveFile(const std::string& path, double map_resolution) {
  return isNav2LatticePath(path) ? readNav2LatticeFile(path, map_resolution)
                                 : readMprimFile(path, map_resolution);
}

void writePrimitiveFile(const std::string& path, const PrimitiveSet& set) {
  if (isNav2LatticePath(path)) {
    writeNav2LatticeFile(path, set);
  } else {
    writeMprimFile(path, set);
  }
}

bool parseMotionModel(const std::string& text, MotionModel* model) {
  if (text == "diff" || text == "differential") {
    *model = MotionModel::kDifferential;
  } else if (text == "ackermann") {
    *model = MotionModel::kAckermann;
  } else if (text == "omni") {
    *model = MotionModel::kOmni;
  } else {
    return false;
  }
  return true;
}

bool parsePrimitiveGenerator(const std::string& text, PrimitiveGenerator* generator) {
  if (text == "near-minimal") {
    *generator = PrimitiveGenerator::kNearMinimal;
  } else if (text == "legacy") {
    *generator = PrimitiveGenerator::kLegacy;
  } else {
    return false;
  }
  return true;
}

const char* primitiveGeneratorName(PrimitiveGenerator generator) {
  return generator == PrimitiveGenerator::kLegacy ? "legacy" : "near-minimal";
}

const char* motionModelName(MotionModel model) {
  switch (model) {
    case MotionModel::kDifferential:
      return "diff";
    case MotionModel::kAckermann:
      return "ackermann";
    case MotionModel::kOmni:
      return "omni";
  }
  return "?";
}

void addBackwardTwins(PrimitiveSet& set, double multiplier) {
  const int n = set.num_headings;
  std::vector<int> opposite(n);
  for (int h = 0; h < n; ++h) {
    opposite[h] = set.headingIndex(set.heading_angles[h] + M_PI);
    if (angleDistance(set.heading_angles[opposite[h]], set.heading_angles[h] + M_PI) > 1e-6) {
      throw LatticeError(
          LatticeError::Kind::kPrimitives,
          "backward motions: heading " + std::to_string(h) + " has no opposite heading");
    }
  }
  std::vector<MotionPrimitive> twins;
  for (const MotionPrimitive& p : set.primitives) {
    if (p.reverse || (p.end_dx == 0 && p.end_dy == 0) || p.poses.size() < 2) continue;
    // Forward motions only: the first step goes the way the robot faces (not sideways).
    const double phi = set.heading_angles[p.start_heading];
    const Pose2D& a = p.poses.front();
    const Pose2D* b = &p.poses[1];
    for (std::size_t k = 2; k < p.poses.size() && std::hypot(b->x - a.x, b->y - a.y) < 1e-9; ++k)
      b = &p.poses[k];
    const double dx = b->x - a.x, dy = b->y - a.y, along = dx * std::cos(phi) + dy * std::sin(phi);
    if (!(along > 0.5 * std::hypot(dx, dy))) continue;
    MotionPrimitive t = p;
    t.start_heading = opposite[p.start_heading];
    t.end_heading = opposite[p.end_heading];
    t.cost_multiplier = multiplier * p.cost_multiplier;
    t.reverse = true;
    for (Pose2D& q : t.poses) q.theta = normalizeAngle(q.theta + M_PI);
    t.poses.front().theta = set.heading_angles[t.start_heading];
    t.poses.back().theta = set.heading_angles[t.end_heading];
    twins.push_back(std::move(t));
  }
  set.primitives.insert(set.primitives.end(), twins.begin(), twins.end());
  detail::numberByHeading(set);
}

}  // namespace lattice
}  // namespace amha
