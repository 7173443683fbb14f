// Run-time parameters <-> dynamic_reconfigure configuration (see reconfigure.h).
#include "amha_planner/ros/reconfigure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <dynamic_reconfigure/Config.h>

#include "amha_planner/lattice/detail/footprint.h"

namespace amha_planner {

namespace {

namespace lat = amha::lattice;

/// The shortest decimal form that reads back as the same double.
std::string exact(double v) {
  char buf[40];
  for (int precision = 6; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

std::string footprintText(const std::vector<std::array<double, 2>>& polygon) {
  if (polygon.empty()) return "";
  std::string s = "[";
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    s += (i ? ", [" : "[") + exact(polygon[i][0]) + ", " + exact(polygon[i][1]) + "]";
  }
  return s + "]";
}

}  // namespace

AmhaPlannerConfig configFromParams(const PlannerParams& p) {
  AmhaPlannerConfig c = AmhaPlannerConfig::__getDefault__();
  const lat::LatticeConfig& l = p.lattice;
  c.algorithm = amha::algorithmName(p.algorithm);
  c.num_inadmissible = l.heuristics.num_inadmissible;
  c.w1 = p.w1;
  c.w2 = p.w2;
  c.dw1 = p.dw1;
  c.dw2 = p.dw2;
  c.queue_schedule = amha::scheduleName(p.queue_schedule);
  c.weight_schedule = amha::weightScheduleName(p.weight_schedule);
  c.certified_ratio = p.certified_ratio;
  c.certified_split = p.certified_split;
  c.final_gap = p.final_gap;
  c.publish_within_iterations = p.publish_within_iterations;
  c.stall_expansions = p.stall_expansions;
  c.stall_w1 = p.stall_w1;
  c.stall_mid_w1 = p.stall_mid_w1;
  c.stall_mid_expansions = p.stall_mid_expansions;
  c.kinematic_radius = l.heuristics.kinematic_radius;
  c.anchor_connectivity = l.heuristics.anchor_connectivity;
  c.inadmissible_heuristics =
      l.heuristics.inadmissible == lat::LatticeConfig::Inadmissible::kPaper ? "paper" : "kinematic";
  c.eps = p.eps;
  c.eps_decrement = p.eps_decrement;
  c.default_time_budget = p.default_time_budget;
  c.max_memory_mb = p.max_memory_mb;
  c.grid_anchor = l.heuristics.grid_anchor;
  c.coarse_anchor = l.heuristics.coarse_anchor;
  c.coarse_block = l.heuristics.coarse_block;
  c.anchor_turn_term = l.heuristics.anchor_turn_term;
  c.inflate_heading_terms = l.heuristics.inflate_heading_terms;
  c.backward_search = l.backward_search;
  c.heuristic_cache_size = l.cache.size;
  c.repair_heuristics = l.cache.repair;
  c.ignore_goal_heading = p.ignore_goal_heading;
  c.start_tolerance = p.start_tolerance;
  c.start_escape_penalty = p.start_escape_penalty;
  c.tf_timeout = p.tf_timeout;
  c.footprint = footprintText(l.robot.footprint);
  c.robot_radius = l.robot.radius;
  c.mprim_file = l.motion.mprim_file;
  c.turning_radius = l.motion.turning_radius;
  c.num_headings = l.motion.num_headings;
  c.allow_reverse = l.motion.allow_reverse;
  c.turn_in_place = l.motion.turn_in_place;
  c.nominal_speed = l.cost.nominal_speed;
  c.time_to_turn_45 = l.cost.time_to_turn_45;
  c.lethal_threshold = p.occupancy.lethal_threshold;
  c.unknown_is_free = p.occupancy.unknown_is_free;
  c.cost_penalty = l.cost.penalty;
  c.marker_spacing = p.marker_spacing;
  c.smooth_path = p.smooth_path;
  return c;
}

bool paramsFromConfig(const AmhaPlannerConfig& c, const PlannerParams& base,
                      const ros::NodeHandle& pnh, PlannerParams* out, std::string* error) {
  auto fail = [&](const std::string& name, const std::string& problem) {
    *error = "parameter " + pnh.resolveName(name) + ": " + problem;
    return false;
  };
  // dynamic_reconfigure clamps numbers into their ranges, but a NaN passes every comparison.
  const std::pair<const char*, double> numbers[] = {
      {"w1", c.w1},
      {"w2", c.w2},
      {"dw1", c.dw1},
      {"dw2", c.dw2},
      {"eps", c.eps},
      {"eps_decrement", c.eps_decrement},
      {"default_time_budget", c.default_time_budget},
      {"max_memory_mb", c.max_memory_mb},
      {"start_tolerance", c.start_tolerance},
      {"start_escape_penalty", c.start_escape_penalty},
      {"tf_timeout", c.tf_timeout},
      {"robot_radius", c.robot_radius},
      {"turning_radius", c.turning_radius},
      {"certified_ratio", c.certified_ratio},
      {"certified_split", c.certified_split},
      {"final_gap", c.final_gap},
      {"kinematic_radius", c.kinematic_radius},
      {"stall_w1", c.stall_w1},
      {"stall_mid_w1", c.stall_mid_w1},
      {"nominal_speed", c.nominal_speed},
      {"time_to_turn_45", c.time_to_turn_45},
      {"cost_penalty", c.cost_penalty},
      {"marker_spacing", c.marker_spacing}};
  for (const auto& [name, v] : numbers) {
    if (!std::isfinite(v)) return fail(name, "expected a number, got " + exact(v));
  }
  // -1 stands for the algorithm's preset (as when the ~parameter is not set).
  for (const auto& [name, v] :
       {std::make_pair("w1", c.w1), std::make_pair("w2", c.w2), std::make_pair("eps", c.eps)}) {
    if (v != -1.0 && v < 1.0)
      return fail(name, exact(v) + " is neither -1 (the algorithm's preset) nor >= 1");
  }
  for (const auto& [name, v] : {std::make_pair("dw1", c.dw1), std::make_pair("dw2", c.dw2),
                                std::make_pair("eps_decrement", c.eps_decrement)}) {
    if (v != -1.0 && v < 0.0)
      return fail(name, exact(v) + " is neither -1 (the algorithm's preset) nor >= 0");
  }
  PlannerParams p = base;
  if (!amha::parseAlgorithm(c.algorithm, &p.algorithm)) {
    return fail("algorithm",
                "unknown algorithm '" + c.algorithm + "' (amha, mha, ara, ana, wastar, astar)");
  }
  if (!amha::parseSchedule(c.queue_schedule, &p.queue_schedule)) {
    return fail("queue_schedule", "unknown schedule '" + c.queue_schedule + "' (rr, dts)");
  }
  if (!amha::parseWeightSchedule(c.weight_schedule, &p.weight_schedule)) {
    return fail("weight_schedule",
                "unknown schedule '" + c.weight_schedule + "' (certified, decrement)");
  }
  if (c.anchor_connectivity != 8 && c.anchor_connectivity != 16) {
    return fail("anchor_connectivity", std::to_string(c.anchor_connectivity) + " is not 8 or 16");
  }
  if (c.inadmissible_heuristics != "kinematic" && c.inadmissible_heuristics != "paper") {
    return fail("inadmissible_heuristics",
                "'" + c.inadmissible_heuristics + "' is not kinematic or paper");
  }
  if (c.num_headings % 8 != 0)
    return fail("num_headings", std::to_string(c.num_headings) + " is not a multiple of 8");
  lat::LatticeConfig& l = p.lattice;
  try {
    l.robot.footprint = footprintFromString(pnh, c.footprint);
  } catch (const std::invalid_argument& e) {
    *error = e.what();
    return false;
  }
  p.w1 = c.w1;
  p.w2 = c.w2;
  p.dw1 = c.dw1;
  p.dw2 = c.dw2;
  p.eps = c.eps;
  p.eps_decrement = c.eps_decrement;
  p.certified_ratio = c.certified_ratio;
  p.certified_split = c.certified_split;
  p.final_gap = c.final_gap;
  p.publish_within_iterations = c.publish_within_iterations;
  p.stall_expansions = c.stall_expansions;
  p.stall_w1 = c.stall_w1;
  p.stall_mid_w1 = c.stall_mid_w1;
  p.stall_mid_expansions = c.stall_mid_expansions;
  l.heuristics.kinematic_radius = c.kinematic_radius;
  l.heuristics.anchor_connectivity = c.anchor_connectivity;
  l.heuristics.inadmissible = c.inadmissible_heuristics == "paper"
                                  ? lat::LatticeConfig::Inadmissible::kPaper
                                  : lat::LatticeConfig::Inadmissible::kKinematic;
  p.default_time_budget = c.default_time_budget;
  p.max_memory_mb = c.max_memory_mb;
  p.ignore_goal_heading = c.ignore_goal_heading;
  p.start_tolerance = c.start_tolerance;
  p.start_escape_penalty = c.start_escape_penalty;
  p.tf_timeout = c.tf_timeout;
  p.marker_spacing = c.marker_spacing;
  p.smooth_path = c.smooth_path;
  p.occupancy.lethal_threshold = c.lethal_threshold;
  p.occupancy.unknown_is_free = c.unknown_is_free;
  l.heuristics.num_inadmissible = c.num_inadmissible;
  l.heuristics.grid_anchor = c.grid_anchor;
  l.heuristics.coarse_anchor = c.coarse_anchor;
  l.heuristics.coarse_block = c.coarse_block;
  l.heuristics.anchor_turn_term = c.anchor_turn_term;
  l.heuristics.inflate_heading_terms = c.inflate_heading_terms;
  l.backward_search = c.backward_search;
  l.cache.size = c.heuristic_cache_size;
  l.cache.repair = c.repair_heuristics;
  l.robot.radius = c.robot_radius;
  l.motion.mprim_file = c.mprim_file;
  l.motion.turning_radius = c.turning_radius;
  l.motion.num_headings = c.num_headings;
  l.motion.allow_reverse = c.allow_reverse;
  l.motion.turn_in_place = c.turn_in_place;
  l.cost.nominal_speed = c.nominal_speed;
  l.cost.time_to_turn_45 = c.time_to_turn_45;
  l.cost.penalty = c.cost_penalty;
  // The weights as a whole, as at start-up.
  amha::PlannerConfig check;
  std::string why;
  if (!searchConfigFor(p, "", 0.0, 0.0, &check, &why)) return fail("algorithm/weights", why);
  *out = std::move(p);
  return true;
}

bool latticeBuilds(const PlannerParams& params, const lat::GridMap* map, std::string* error) {
  try {
    const lat::RobotFootprint footprint = lat::RobotFootprint::fromConfig(params.lattice);
    if (map == nullptr) return true;
    const double res = map->resolution;
    // The one check of a build that depends on the map's size, made here against the current
    // map: the probe below is only as large as the robot.
    footprint.checkFitsMap(map->width, map->height, res);
    const double inscribed = footprint.inscribed_radius;
    // A free map of that resolution, just large enough for the robot: what else a build checks
    // (the primitives against the resolution, the footprint and its sweeps, the cost model) does
    // not depend on the map's cells.
    const int side = std::max(16, static_cast<int>(std::ceil(2.0 * inscribed / res)) + 2);
    auto probe_map = std::make_shared<lat::GridMap>();
    probe_map->width = probe_map->height = side;
    probe_map->resolution = res;
    probe_map->cost.assign(static_cast<std::size_t>(side) * side, lat::kFreeCost);
    lat::LatticePlanner probe(probe_map, params.lattice);
    return true;
  } catch (const std::exception& e) {
    *error = e.what();
    return false;
  }
}

std::string changedParameters(const AmhaPlannerConfig& from, const AmhaPlannerConfig& to) {
  dynamic_reconfigure::Config a, b;
  from.__toMessage__(a);
  to.__toMessage__(b);
  std::ostringstream s;
  auto each = [&](const auto& olds, const auto& news, auto text) {
    for (const auto& n : news) {
      for (const auto& o : olds) {
        if (o.name != n.name || o.value == n.value) continue;
        s << (s.tellp() > 0 ? ", " : "") << n.name << " " << text(o.value) << " -> "
          << text(n.value);
      }
    }
  };
  each(a.bools, b.bools, [](bool v) { return std::string(v ? "true" : "false"); });
  each(a.ints, b.ints, [](int v) { return std::to_string(v); });
  each(a.doubles, b.doubles, [](double v) { return exact(v); });
  each(a.strs, b.strs, [](const std::string& v) { return "'" + v + "'"; });
  return s.str();
}

}  // namespace amha_planner
