// Nav2 lattice primitive files (the JSON nav2_smac_planner's lattice_primitives generator
// writes), validated field by field so that every error names the file, the field and the value.
#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "amha_planner/lattice/motion_primitives.h"
#include "primitive_geometry.h"

namespace amha {
namespace lattice {

namespace {

using nlohmann::json;

// An end pose may miss its cell centre and heading by this much (the files round to 5 decimals).
constexpr double kEndCellTolerance = 0.01;   // cells
constexpr double kEndAngleTolerance = 1e-3;  // radians

std::string str(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// A value as it stands in the file, shortened for messages.
std::string shown(const json& v) {
  std::string s = v.dump();
  return s.size() > 40 ? s.substr(0, 37) + "..." : s;
}

// Reads fields of one JSON object, failing with "file: where: 'field' problem".
class Fields {
 public:
  Fields(const json& object, std::string file, std::string where)
      : o_(object), file_(std::move(file)), where_(std::move(where)) {
    if (!o_.is_object()) fail("must be a JSON object, not " + shown(o_));
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw LatticeError(LatticeError::Kind::kPrimitives, file_ + ": " + where_ + ": " + what);
  }

  const json& field(const char* name, const char* expected) const {
    const auto it = o_.find(name);
    if (it == o_.end()) fail(std::string("missing '") + name + "' (" + expected + ")");
    return *it;
  }
  double number(const char* name, double lo, double hi, const char* expected) const {
    const json& v = field(name, expected);
    if (!v.is_number())
      fail(std::string("'") + name + "' must be " + expected + ", not " + shown(v));
    const double d = v.get<double>();
    if (!(d >= lo && d <= hi))
      fail(std::string("'") + name + "' " + str(d) + " is not " + expected);
    return d;
  }
  long integer(const char* name, long lo, long hi) const {
    const std::string expected = "an integer in " + std::to_string(lo) + ".." + std::to_string(hi);
    const json& v = field(name, expected.c_str());
    if (!v.is_number_integer())
      fail(std::string("'") + name + "' must be " + expected + ", not " + shown(v));
    const long i =
        v.is_number_unsigned()
            ? static_cast<long>(std::min<std::uint64_t>(v.get<std::uint64_t>(), 1ull << 62))
            : v.get<long>();
    if (i < lo || i > hi)
      fail(std::string("'") + name + "' " + std::to_string(i) + " is not " + expected);
    return i;
  }
  bool boolean(const char* name) const {
    const json& v = field(name, "true or false");
    if (!v.is_boolean()) fail(std::string("'") + name + "' must be true or false, not " + shown(v));
    return v.get<bool>();
  }
  const json& array(const char* name, const char* expected) const {
    const json& v = field(name, expected);
    if (!v.is_array())
      fail(std::string("'") + name + "' must be " + expected + ", not " + shown(v));
    return v;
  }

 private:
  const json& o_;
  std::string file_, where_;
};

void readMetadata(const Fields& f, double map_resolution, PrimitiveSet* set, long* count) {
  const json& model = f.field("motion_model", "\"ackermann\", \"diff\" or \"omni\"");
  MotionModel parsed;
  if (!model.is_string() || model.get<std::string>() == "differential" ||
      !parseMotionModel(model.get<std::string>(), &parsed)) {
    f.fail("'motion_model' must be \"ackermann\", \"diff\" or \"omni\", not " + shown(model));
  }
  set->motion_model = model.get<std::string>();
  set->min_turning_radius = f.number("turning_radius", 0.0, 1e6, "a radius >= 0 in metres");
  set->resolution = f.number("grid_resolution", kMinResolution, kMaxResolution,
                             "a resolution in metres in [0.001, 1000]");
  if (map_resolution > 0.0 && std::fabs(set->resolution - map_resolution) > 1e-6) {
    f.fail("'grid_resolution' " + str(set->resolution) + " does not match the map's resolution " +
           str(map_resolution));
  }
  set->num_headings = static_cast<int>(f.integer("num_of_headings", 1, 1024));
  const json& angles = f.array("heading_angles", "an array of num_of_headings angles in radians");
  if (angles.size() != static_cast<std::size_t>(set->num_headings)) {
    f.fail("'heading_angles' has " + std::to_string(angles.size()) +
           " angles, not num_of_headings = " + std::to_string(set->num_headings));
  }
  for (std::size_t i = 0; i < angles.size(); ++i) {
    const json& a = angles[i];
    const std::string name = "'heading_angles'[" + std::to_string(i) + "] ";
    if (!a.is_number()) f.fail(name + "must be an angle in radians, not " + shown(a));
    const double v = a.get<double>();
    if (!(v >= 0.0 && v < 2.0 * M_PI)) f.fail(name + str(v) + " is not in [0, 2 pi)");
    if (i > 0 && !(v > set->heading_angles.back()))
      f.fail(name + str(v) + " is not greater than the angle before it");
    set->heading_angles.push_back(v);
  }
  set->uniform = false;  // the angles are listed (SBPL's non-uniform variant)
  *count = f.integer("number_of_trajectories", 1, 1000000);
}

MotionPrimitive readPrimitive(const json& j, std::size_t k, const std::string& file,
                              const PrimitiveSet& set) {
  std::string where = "primitives[" + std::to_string(k) + "]";
  if (j.is_object() && j.contains("trajectory_id"))
    where += " (trajectory_id " + shown(j["trajectory_id"]) + ")";
  const Fields f(j, file, where);
  const long n = set.num_headings;
  MotionPrimitive p;
  f.integer("trajectory_id", 0, 1L << 40);
  p.start_heading = static_cast<int>(f.integer("start_angle_index", 0, n - 1));
  p.end_heading = static_cast<int>(f.integer("end_angle_index", 0, n - 1));
  const bool left = f.boolean("left_turn");
  const double radius =
      f.number("trajectory_radius", 0.0, 1e6, "a radius >= 0 in metres (0: no arc)");
  p.turning_radius = radius == 0.0 ? 0.0 : left ? radius : -radius;
  f.number("trajectory_length", 0.0, 1e6, "a length >= 0 in metres");
  p.arc_length = f.number("arc_length", 0.0, 1e6, "a length >= 0 in metres");
  p.straight_length = f.number("straight_length", 0.0, 1e6, "a length >= 0 in metres");
  const json& poses = f.array("poses", "an array of [x, y, yaw] poses");
  if (poses.empty() || poses.size() > 100000)
    f.fail("'poses' has " + std::to_string(poses.size()) + " poses (1..100000)");
  const double start_angle = set.heading_angles[p.start_heading];
  p.poses.reserve(poses.size() + 1);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const json& q = poses[i];
    bool ok = q.is_array() && q.size() == 3;
    for (std::size_t c = 0; ok && c < 3; ++c)
      ok = q[c].is_number() && std::isfinite(q[c].get<double>());
    if (!ok)
      f.fail("'poses'[" + std::to_string(i) + "] must be [x, y, yaw] (3 finite numbers), not " +
             shown(q));
    const Pose2D pose{q[0].get<double>(), q[1].get<double>(), q[2].get<double>()};
    // Nav2 leaves the start pose out of moves (turns on the spot list it): put it back.
    if (i == 0 &&
        (std::hypot(pose.x, pose.y) > 1e-6 || angleDistance(pose.theta, start_angle) > 1e-6)) {
      p.poses.push_back({0.0, 0.0, start_angle});
    }
    p.poses.push_back(pose);
  }
  const double res = set.resolution;
  const double length = detail::polylineLength(p.poses);
  if (!(length / res <= detail::kMaxPrimitiveCells)) {
    f.fail("its poses are " + str(length / res) + " cells long (at most " +
           str(detail::kMaxPrimitiveCells) + ")");
  }
  const Pose2D& last = p.poses.back();
  const double ex = last.x / res, ey = last.y / res;
  p.end_dx = static_cast<int>(std::lround(ex));
  p.end_dy = static_cast<int>(std::lround(ey));
  if (std::fabs(ex - p.end_dx) > kEndCellTolerance ||
      std::fabs(ey - p.end_dy) > kEndCellTolerance ||
      angleDistance(last.theta, set.heading_angles[p.end_heading]) > kEndAngleTolerance) {
    f.fail("the last pose " + shown(poses.back()) + " is not a cell centre at end heading " +
           std::to_string(p.end_heading) + " (" + str(set.heading_angles[p.end_heading]) + " rad)");
  }
  return p;
}

}  // namespace

PrimitiveSet readNav2Lattice(std::istream& in, const std::string& name, double map_resolution) {
  json doc;
  try {
    doc = json::parse(in);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for a number like 1e999
    std::string what = e.what();
    const std::size_t at = what.find("] ");
    throw LatticeError(
        LatticeError::Kind::kPrimitives,
        name + ": not valid JSON: " + (at == std::string::npos ? what : what.substr(at + 2)));
  }
  const Fields root(doc, name, "the document");
  PrimitiveSet set;
  long count = 0;
  readMetadata(Fields(root.field("lattice_metadata", "an object"), name, "lattice_metadata"),
               map_resolution, &set, &count);
  const json& prims = root.array("primitives", "an array of primitives");
  if (prims.size() != static_cast<std::size_t>(count)) {
    root.fail("'primitives' has " + std::to_string(prims.size()) +
              " primitives, but lattice_metadata's "
              "number_of_trajectories says " +
              std::to_string(count));
  }
  set.primitives.reserve(prims.size());
  for (std::size_t k = 0; k < prims.size(); ++k)
    set.primitives.push_back(readPrimitive(prims[k], k, name, set));
  detail::numberByHeading(set);
  detail::dropCopies(set);
  detail::numberByHeading(set);
  for (int h = 0; h < set.num_headings; ++h) {
    const auto r = set.range(h);
    if (r.first == r.second)
      root.fail("heading " + std::to_string(h) +
                " has no primitives (every start_angle_index needs some)");
  }
  return set;
}

PrimitiveSet readNav2LatticeFile(const std::string& path, double map_resolution) {
  std::ifstream in(path);
  if (!in) throw LatticeError(LatticeError::Kind::kPrimitives, path + ": cannot open the file");
  return readNav2Lattice(in, path, map_resolution);
}

}  // namespace lattice
}  // namespace amha
