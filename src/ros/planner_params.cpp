// Parameter loading and request overrides (see planner_params.h).
#include "amha_planner/ros/planner_params.h"

#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <XmlRpcValue.h>

#include "amha_planner/lattice/motion_primitives.h"

namespace amha_planner {

namespace {

[[noreturn]] void bad(const ros::NodeHandle& pnh, const std::string& name,
                      const std::string& problem) {
  throw std::invalid_argument("parameter " + pnh.resolveName(name) + ": " + problem);
}

double toDouble(const XmlRpc::XmlRpcValue& v, bool* ok) {
  *ok = true;
  if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) return static_cast<double>(v);
  if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) return static_cast<int>(v);
  *ok = false;
  return 0.0;
}

double getDouble(const ros::NodeHandle& pnh, const std::string& name, double fallback, double min,
                 double max) {
  XmlRpc::XmlRpcValue v;
  if (!pnh.getParam(name, v)) return fallback;
  bool ok = false;
  const double d = toDouble(v, &ok);
  if (!ok) bad(pnh, name, "expected a number");
  if (!std::isfinite(d) || d < min || d > max) {
    std::ostringstream s;
    s << d << " is outside [" << min << ", " << max << "]";
    bad(pnh, name, s.str());
  }
  return d;
}

int getInt(const ros::NodeHandle& pnh, const std::string& name, int fallback, int min, int max) {
  XmlRpc::XmlRpcValue v;
  if (!pnh.getParam(name, v)) return fallback;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeInt) bad(pnh, name, "expected an integer");
  const int i = static_cast<int>(v);
  if (i < min || i > max) {
    std::ostringstream s;
    s << i << " is outside [" << min << ", " << max << "]";
    bad(pnh, name, s.str());
  }
  return i;
}

bool getBool(const ros::NodeHandle& pnh, const std::string& name, bool fallback) {
  XmlRpc::XmlRpcValue v;
  if (!pnh.getParam(name, v)) return fallback;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeBoolean) bad(pnh, name, "expected true or false");
  return static_cast<bool>(v);
}

std::string getString(const ros::NodeHandle& pnh, const std::string& name,
                      const std::string& fallback) {
  XmlRpc::XmlRpcValue v;
  if (!pnh.getParam(name, v)) return fallback;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeString) bad(pnh, name, "expected a string");
  return static_cast<std::string>(v);
}

// A footprint is a list of [x, y] points, as in costmap_2d: either a YAML list or the string
// form "[[x, y], [x, y], ...]" that costmap_2d also accepts.
std::vector<std::array<double, 2>> parseFootprintString(const ros::NodeHandle& pnh,
                                                        const std::string& text) {
  std::vector<std::array<double, 2>> out;
  std::vector<double> numbers;
  std::string cleaned;
  int depth = 0;
  for (char c : text) {
    if (c == '[') {
      ++depth;
      if (depth > 2) bad(pnh, "footprint", "too deeply nested: " + text);
      cleaned += ' ';
    } else if (c == ']') {
      --depth;
      if (depth < 0) bad(pnh, "footprint", "unbalanced brackets: " + text);
      cleaned += ' ';
    } else if (c == ',') {
      cleaned += ' ';
    } else {
      cleaned += c;
    }
  }
  if (depth != 0) bad(pnh, "footprint", "unbalanced brackets: " + text);
  std::istringstream in(cleaned);
  double d;
  while (in >> d) numbers.push_back(d);
  if (!in.eof()) bad(pnh, "footprint", "not a list of [x, y] points: " + text);
  if (numbers.size() % 2 != 0) bad(pnh, "footprint", "odd number of coordinates: " + text);
  for (std::size_t i = 0; i + 1 < numbers.size(); i += 2)
    out.push_back({numbers[i], numbers[i + 1]});
  return out;
}

std::vector<std::array<double, 2>> getFootprint(const ros::NodeHandle& pnh) {
  XmlRpc::XmlRpcValue v;
  if (!pnh.getParam("footprint", v)) return {};
  std::vector<std::array<double, 2>> out;
  if (v.getType() == XmlRpc::XmlRpcValue::TypeString) {
    out = parseFootprintString(pnh, static_cast<std::string>(v));
  } else if (v.getType() == XmlRpc::XmlRpcValue::TypeArray) {
    for (int i = 0; i < v.size(); ++i) {
      XmlRpc::XmlRpcValue& pt = v[i];
      if (pt.getType() != XmlRpc::XmlRpcValue::TypeArray || pt.size() != 2) {
        bad(pnh, "footprint", "point " + std::to_string(i) + " is not an [x, y] pair");
      }
      bool okx = false, oky = false;
      const double x = toDouble(pt[0], &okx), y = toDouble(pt[1], &oky);
      if (!okx || !oky || !std::isfinite(x) || !std::isfinite(y)) {
        bad(pnh, "footprint", "point " + std::to_string(i) + " has a non-numeric coordinate");
      }
      out.push_back({x, y});
    }
  } else {
    bad(pnh, "footprint", "expected a list of [x, y] points");
  }
  if (!out.empty() && out.size() < 3) bad(pnh, "footprint", "needs at least 3 points");
  return out;
}

bool validWeight(double w) { return w >= 1.0 && w <= amha::kMaxWeight; }  // NaN fails both

}  // namespace

std::vector<std::array<double, 2>> footprintFromString(const ros::NodeHandle& pnh,
                                                       const std::string& text) {
  std::vector<std::array<double, 2>> out = parseFootprintString(pnh, text);
  if (!out.empty() && out.size() < 3) bad(pnh, "footprint", "needs at least 3 points");
  return out;
}

std::string normaliseFrame(const std::string& frame) {
  return !frame.empty() && frame[0] == '/' ? frame.substr(1) : frame;
}

PlannerParams loadPlannerParams(const ros::NodeHandle& pnh) {
  PlannerParams p;
  auto& l = p.lattice;
  // Robot.
  l.robot.footprint = getFootprint(pnh);
  // Robots of a few metres at most: a larger one (a building-sized disc) only fits a map of
  // kilometres, and its sweeps are refused on fine maps anyway (LatticeGraph, kMaxSweptCells).
  // The map decides the rest when it comes: a robot wider than it is refused, and NO_MAP says so.
  l.robot.radius = getDouble(pnh, "robot_radius", l.robot.radius, 1e-3, kMaxRobotRadius);
  // Motion primitives: a file, or generated.
  l.motion.mprim_file = getString(pnh, "mprim_file", "");
  l.motion.turning_radius =
      getDouble(pnh, "turning_radius", l.motion.turning_radius, 1e-3, kMaxTurningRadius);
  l.motion.num_headings = getInt(pnh, "num_headings", l.motion.num_headings, 8, 1024);
  if (l.motion.num_headings % 8 != 0) bad(pnh, "num_headings", "must be a multiple of 8");
  l.motion.allow_reverse = getBool(pnh, "allow_reverse", l.motion.allow_reverse);
  l.motion.turn_in_place = getBool(pnh, "turn_in_place", l.motion.turn_in_place);
  const std::string model =
      getString(pnh, "motion_model", amha::lattice::motionModelName(l.motion.model));
  if (!amha::lattice::parseMotionModel(model, &l.motion.model)) {
    bad(pnh, "motion_model", "'" + model + "' is not diff, ackermann or omni");
  }
  const std::string generator = getString(pnh, "primitive_generator", "near-minimal");
  if (!amha::lattice::parsePrimitiveGenerator(generator, &l.motion.generator)) {
    bad(pnh, "primitive_generator", "'" + generator + "' is not near-minimal or legacy");
  }
  l.cost.reverse_multiplier =
      getDouble(pnh, "reverse_penalty", l.cost.reverse_multiplier, 1e-3, 1e6);
  l.cost.penalty = getDouble(pnh, "cost_penalty", l.cost.penalty, 0.0, 1e6);
  l.heuristics.num_inadmissible =
      getInt(pnh, "num_inadmissible", l.heuristics.num_inadmissible, 0, 3);
  l.cost.nominal_speed = getDouble(pnh, "nominal_speed", l.cost.nominal_speed, 1e-3, 100.0);
  l.cost.time_to_turn_45 = getDouble(pnh, "time_to_turn_45", l.cost.time_to_turn_45, 0.0, 1000.0);
  l.heuristics.grid_anchor = getBool(pnh, "grid_anchor", l.heuristics.grid_anchor);
  l.heuristics.coarse_anchor = getBool(pnh, "coarse_anchor", l.heuristics.coarse_anchor);
  l.heuristics.coarse_block =
      getInt(pnh, "coarse_block", l.heuristics.coarse_block, 0, amha::lattice::kMaxCoarseBlock);
  l.heuristics.kinematic_radius =
      getDouble(pnh, "kinematic_radius", l.heuristics.kinematic_radius, 0.0, 100.0);
  l.heuristics.anchor_connectivity =
      getInt(pnh, "anchor_connectivity", l.heuristics.anchor_connectivity, 8, 16);
  if (l.heuristics.anchor_connectivity != 8 && l.heuristics.anchor_connectivity != 16)
    bad(pnh, "anchor_connectivity", "must be 8 or 16");
  const std::string inadmissible = getString(pnh, "inadmissible_heuristics", "kinematic");
  if (inadmissible != "kinematic" && inadmissible != "paper") {
    bad(pnh, "inadmissible_heuristics", "must be kinematic or paper, not '" + inadmissible + "'");
  }
  l.heuristics.inadmissible = inadmissible == "paper"
                                  ? amha::lattice::LatticeConfig::Inadmissible::kPaper
                                  : amha::lattice::LatticeConfig::Inadmissible::kKinematic;
  l.heuristics.anchor_turn_term = getBool(pnh, "anchor_turn_term", l.heuristics.anchor_turn_term);
  l.heuristics.inflate_heading_terms =
      getBool(pnh, "inflate_heading_terms", l.heuristics.inflate_heading_terms);
  l.backward_search = getBool(pnh, "backward_search", l.backward_search);
  l.cache.size = getInt(pnh, "heuristic_cache_size", l.cache.size, 1, 64);
  l.cache.repair = getBool(pnh, "repair_heuristics", l.cache.repair);
  // Map.
  p.occupancy.lethal_threshold =
      getInt(pnh, "lethal_threshold", p.occupancy.lethal_threshold, 1, 100);
  p.occupancy.unknown_is_free = getBool(pnh, "unknown_is_free", p.occupancy.unknown_is_free);
  p.max_map_cells = static_cast<std::size_t>(
      getInt(pnh, "max_map_cells", static_cast<int>(p.max_map_cells), 1, 1 << 30));
  // Algorithm.
  const std::string name = getString(pnh, "algorithm", amha::algorithmName(p.algorithm));
  if (!amha::parseAlgorithm(name, &p.algorithm)) {
    bad(pnh, "algorithm", "unknown algorithm '" + name + "' (amha, mha, ara, ana, wastar, astar)");
  }
  p.w1 = getDouble(pnh, "w1", -1, 1.0, amha::kMaxWeight);
  p.w2 = getDouble(pnh, "w2", -1, 1.0, amha::kMaxWeight);
  p.dw1 = getDouble(pnh, "dw1", -1, 0.0, amha::kMaxWeight);
  p.dw2 = getDouble(pnh, "dw2", -1, 0.0, amha::kMaxWeight);
  p.eps = getDouble(pnh, "eps", -1, 1.0, amha::kMaxWeight);
  const std::string schedule =
      getString(pnh, "queue_schedule", amha::scheduleName(p.queue_schedule));
  if (!amha::parseSchedule(schedule, &p.queue_schedule)) {
    bad(pnh, "queue_schedule", "unknown schedule '" + schedule + "' (rr, dts)");
  }
  p.eps_decrement = getDouble(pnh, "eps_decrement", -1, 0.0, amha::kMaxWeight);
  const std::string weights =
      getString(pnh, "weight_schedule", amha::weightScheduleName(p.weight_schedule));
  if (!amha::parseWeightSchedule(weights, &p.weight_schedule)) {
    bad(pnh, "weight_schedule", "unknown schedule '" + weights + "' (certified, decrement)");
  }
  p.certified_ratio = getDouble(pnh, "certified_ratio", p.certified_ratio, 0.0, 0.999);
  p.certified_split = getDouble(pnh, "certified_split", p.certified_split, 0.0, 1.0);
  p.final_gap = getDouble(pnh, "final_gap", p.final_gap, 0.0, 1e3);
  p.publish_within_iterations =
      getBool(pnh, "publish_within_iterations", p.publish_within_iterations);
  p.stall_expansions = getInt(pnh, "stall_expansions", p.stall_expansions, 0, 1 << 30);
  p.stall_w1 = getDouble(pnh, "stall_w1", p.stall_w1, 1.0, amha::kMaxWeight);
  p.stall_mid_w1 = getDouble(pnh, "stall_mid_w1", p.stall_mid_w1, 1.0, amha::kMaxWeight);
  p.stall_mid_expansions = getInt(pnh, "stall_mid_expansions", p.stall_mid_expansions, 0, 1 << 30);
  p.default_time_budget = getDouble(pnh, "default_time_budget", p.default_time_budget, 1e-3, 1e6);
  p.max_memory_mb = getDouble(pnh, "max_memory_mb", p.max_memory_mb, 1.0, 1e7);
  p.ignore_goal_heading = getBool(pnh, "ignore_goal_heading", p.ignore_goal_heading);
  p.start_tolerance = getDouble(pnh, "start_tolerance", p.start_tolerance, 0.0, 1e3);
  p.start_escape_penalty = getDouble(pnh, "start_escape_penalty", p.start_escape_penalty, 1.0, 1e3);
  p.smooth_path = getBool(pnh, "smooth_path", p.smooth_path);
  // Frames and server.
  p.global_frame = normaliseFrame(getString(pnh, "global_frame", p.global_frame));
  p.robot_base_frame = normaliseFrame(getString(pnh, "robot_base_frame", p.robot_base_frame));
  if (p.global_frame.empty()) bad(pnh, "global_frame", "must not be empty");
  if (p.robot_base_frame.empty()) bad(pnh, "robot_base_frame", "must not be empty");
  p.tf_timeout = getDouble(pnh, "tf_timeout", p.tf_timeout, 0.0, 60.0);
  p.max_queued_requests = getInt(pnh, "max_queued_requests", p.max_queued_requests, 0, 64);
  p.marker_spacing = getDouble(pnh, "marker_spacing", p.marker_spacing, 0.01, 1e3);
  p.release_freed_memory = getBool(pnh, "release_freed_memory", p.release_freed_memory);
  // Check the search configuration once, so a bad weight fails at start-up, not per request.
  amha::PlannerConfig check;
  std::string error;
  if (!searchConfigFor(p, "", 0.0, 0.0, &check, &error)) bad(pnh, "algorithm/weights", error);
  return p;
}

bool searchConfigFor(const PlannerParams& params, const std::string& algorithm_name, double w1,
                     double w2, amha::PlannerConfig* out, std::string* error) {
  amha::Algorithm algorithm = params.algorithm;
  if (!algorithm_name.empty() && !amha::parseAlgorithm(algorithm_name, &algorithm)) {
    *error = "unknown algorithm '" + algorithm_name + "' (amha, mha, ara, ana, wastar, astar)";
    return false;
  }
  for (const auto& [name, w] : {std::pair<const char*, double>{"w1", w1}, {"w2", w2}}) {
    if (w != 0.0 && !validWeight(w)) {
      std::ostringstream s;
      s << name << " " << w << " is outside [1, " << amha::kMaxWeight
        << "] (0 keeps the configured value)";
      *error = s.str();
      return false;
    }
  }
  amha::PlannerConfig c = amha::lattice::defaultPlannerConfig(algorithm);
  if (algorithm == amha::Algorithm::kAmhaStar) {
    c.weight_schedule = params.weight_schedule;
    c.certified_ratio = params.certified_ratio;
    c.certified_split = params.certified_split;
    c.final_gap = params.final_gap;
    c.publish_within_iterations = params.publish_within_iterations;
    c.stall_expansions = static_cast<std::uint64_t>(params.stall_expansions);
    c.stall_w1 = params.stall_w1;
    c.stall_mid_w1 = params.stall_mid_w1;
    c.stall_mid_expansions = static_cast<std::uint64_t>(params.stall_mid_expansions);
  }
  // ~eps and ~eps_decrement are ARA*'s and weighted A*'s w1 and dw1; a negative parameter is
  // unset, and the request's w1, w2 (0: unset) come last.
  auto given = [](double v) { return v >= 0 ? std::optional<double>(v) : std::nullopt; };
  const bool eps =
      algorithm == amha::Algorithm::kAraStar || algorithm == amha::Algorithm::kWeightedAStar;
  amha::WeightChoice weights{given(eps ? params.eps : params.w1), given(params.w2),
                             given(eps ? params.eps_decrement : params.dw1), given(params.dw2)};
  if (w1 != 0.0) weights.w1 = w1;
  if (w2 != 0.0) weights.w2 = w2;
  amha::applyWeights(weights, &c);
  if (amha::algorithmSpecs(algorithm).queue_schedule) c.schedule = params.queue_schedule;
  // The lattice offers num_inadmissible heuristics; the search may use them all.
  try {
    amha::makePlanner(c);  // the weights and schedule as a whole
  } catch (const std::invalid_argument& e) {
    *error = e.what();
    return false;
  }
  *out = c;
  return true;
}

}  // namespace amha_planner
