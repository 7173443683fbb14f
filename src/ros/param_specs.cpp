// The server's parameters in one list (see param_specs.h).
#include "amha_planner/ros/param_specs.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <type_traits>
#include <utility>

#include "amha_planner/lattice/motion_primitives.h"

namespace amha_planner {

namespace {

namespace lat = amha::lattice;
using Type = ParamSpec::Type;

/// The shortest decimal form that reads back as the same double.
std::string exact(double v) {
  char buf[40];
  for (int precision = 6; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

// A footprint in costmap_2d's string form "[[x, y], [x, y], ...]" ("" or "[]": none) into
// `out`, which a refused one leaves as it was.
std::string parseFootprint(const std::string& text, std::vector<std::array<double, 2>>* out) {
  std::string cleaned;
  int depth = 0;
  for (char c : text) {
    if (c == '[') {
      if (++depth > 2) return "too deeply nested: " + text;
      cleaned += ' ';
    } else if (c == ']') {
      if (--depth < 0) return "unbalanced brackets: " + text;
      cleaned += ' ';
    } else {
      cleaned += c == ',' ? ' ' : c;
    }
  }
  if (depth != 0) return "unbalanced brackets: " + text;
  std::istringstream in(cleaned);
  std::vector<double> numbers;
  double d;
  while (in >> d) numbers.push_back(d);
  if (!in.eof()) return "not a list of [x, y] points: " + text;
  if (numbers.size() % 2 != 0) return "odd number of coordinates: " + text;
  std::vector<std::array<double, 2>> points;
  for (std::size_t i = 0; i + 1 < numbers.size(); i += 2) {
    if (!std::isfinite(numbers[i]) || !std::isfinite(numbers[i + 1]))
      return "point " + std::to_string(i / 2) + " has a non-numeric coordinate";
    points.push_back({numbers[i], numbers[i + 1]});
  }
  if (points.size() == 1 || points.size() == 2) return "needs at least 3 points";
  *out = std::move(points);
  return "";
}

std::string footprintText(const std::vector<std::array<double, 2>>& polygon) {
  if (polygon.empty()) return "";
  std::string s = "[";
  for (std::size_t i = 0; i < polygon.size(); ++i)
    s += (i ? ", [" : "[") + exact(polygon[i][0]) + ", " + exact(polygon[i][1]) + "]";
  return s + "]";
}

// A field of PlannerParams: `field` is a lambda (auto& p) -> auto& { return p.member; }, for
// const and mutable PlannerParams alike.
template <class Field>
using FieldType = std::decay_t<decltype(std::declval<Field>()(std::declval<PlannerParams&>()))>;

// A number, an integer, a switch or text stored as it is; `check` (optional, integers) refuses
// values the range allows but the server cannot use.
template <class Field>
ParamSpec plain(const char* name, Field field, double min = 0.0, double max = 0.0,
                std::function<std::string(double)> check = nullptr) {
  using T = FieldType<Field>;
  ParamSpec s;
  s.name = name;
  s.min = min;
  s.max = max;
  if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
    // Integers of any width travel as int (their ranges fit it).
    s.type = Type::kInt;
    s.get = [field](const PlannerParams& p) { return ParamValue(static_cast<int>(field(p))); };
    s.set = [field, check](const ParamValue& v, PlannerParams* p) {
      const int i = std::get<int>(v);
      std::string why = check ? check(i) : std::string();
      if (why.empty()) field(*p) = static_cast<T>(i);
      return why;
    };
  } else {
    static_assert(
        std::is_same_v<T, bool> || std::is_same_v<T, double> || std::is_same_v<T, std::string>,
        "a parameter is a bool, an integer, a double or text");
    s.type = std::is_same_v<T, bool>     ? Type::kBool
             : std::is_same_v<T, double> ? Type::kDouble
                                         : Type::kString;
    s.get = [field](const PlannerParams& p) { return ParamValue(field(p)); };
    s.set = [field](const ParamValue& v, PlannerParams* p) {
      field(*p) = std::get<T>(v);
      return std::string();
    };
  }
  return s;
}

// A weight whose -1 means the algorithm's preset.
template <class Field>
ParamSpec weight(const char* name, Field field, double min) {
  ParamSpec s = plain(name, field, min, amha::kMaxWeight);
  s.minus_one_is_preset = true;
  return s;
}

// One of a few names, stored as an enum: `parse` and `print` convert, `names` lists them.
template <class Field, class Enum = FieldType<Field>>
ParamSpec choice(const char* name, Field field, bool (*parse)(const std::string&, Enum*),
                 const char* (*print)(Enum), const char* what, const char* names) {
  ParamSpec s;
  s.name = name;
  s.type = Type::kString;
  s.get = [field, print](const PlannerParams& p) {
    return ParamValue(std::string(print(field(p))));
  };
  s.set = [field, parse, what, names](const ParamValue& v, PlannerParams* p) {
    const std::string& text = std::get<std::string>(v);
    if (parse(text, &field(*p))) return std::string();
    return std::string("unknown ") + what + " '" + text + "' (" + names + ")";
  };
  return s;
}

ParamSpec startUpOnly(ParamSpec s) {
  s.reconfigurable = false;
  return s;
}

// A frame id without its leading '/' (tf2's have none), never empty.
template <class Field>
ParamSpec frame(const char* name, Field field) {
  ParamSpec s = startUpOnly(plain(name, field));
  s.set = [field](const ParamValue& v, PlannerParams* p) {
    const std::string f = normaliseFrame(std::get<std::string>(v));
    if (f.empty()) return std::string("must not be empty");
    field(*p) = f;
    return std::string();
  };
  return s;
}

// A lambda (auto& p) -> auto& { return p.member; }, as plain(), choice() and frame() take fields.
#define AMHA_FIELD(member) \
  [](auto& p) -> auto& { return p.member; }

std::vector<ParamSpec> makeSpecs() {
  constexpr double kHuge = 1e6;
  constexpr int kMaxCount = 1 << 30;
  const auto multiple_of_8 = [](double n) {
    return std::fmod(n, 8.0) == 0.0 ? "" : exact(n) + " is not a multiple of 8";
  };
  const auto eight_or_16 = [](double n) {
    return n == 8.0 || n == 16.0 ? "" : exact(n) + " is not 8 or 16";
  };
  ParamSpec footprint;
  footprint.name = "footprint";
  footprint.type = Type::kString;
  footprint.get = [](const PlannerParams& p) {
    return ParamValue(footprintText(p.lattice.robot.footprint));
  };
  footprint.set = [](const ParamValue& v, PlannerParams* p) {
    return parseFootprint(std::get<std::string>(v), &p->lattice.robot.footprint);
  };
  // Robots of a few metres at most: a larger one (a building-sized disc) only fits a map of
  // kilometres, and its sweeps are refused on fine maps anyway (LatticeGraph, kMaxSweptCells).
  // The map decides the rest when it comes: a robot wider than it is refused, and NO_MAP says so.
  return {
      footprint,
      plain("robot_radius", AMHA_FIELD(lattice.robot.radius), 1e-3, kMaxRobotRadius),
      plain("mprim_file", AMHA_FIELD(lattice.motion.mprim_file)),
      choice("primitive_generator", AMHA_FIELD(lattice.motion.generator),
             lat::parsePrimitiveGenerator, lat::primitiveGeneratorName, "generator",
             "near-minimal, legacy"),
      choice("motion_model", AMHA_FIELD(lattice.motion.model), lat::parseMotionModel,
             lat::motionModelName, "motion model", "diff, ackermann, omni"),
      plain("turning_radius", AMHA_FIELD(lattice.motion.turning_radius), 1e-3, kMaxTurningRadius),
      plain("num_headings", AMHA_FIELD(lattice.motion.num_headings), 8, 1024, multiple_of_8),
      plain("allow_reverse", AMHA_FIELD(lattice.motion.allow_reverse)),
      plain("reverse_penalty", AMHA_FIELD(lattice.cost.reverse_multiplier), 1e-3, kHuge),
      plain("turn_in_place", AMHA_FIELD(lattice.motion.turn_in_place)),
      plain("nominal_speed", AMHA_FIELD(lattice.cost.nominal_speed), 1e-3, 100.0),
      plain("time_to_turn_45", AMHA_FIELD(lattice.cost.time_to_turn_45), 0.0, 1000.0),
      plain("lethal_threshold", AMHA_FIELD(occupancy.lethal_threshold), 1, 100),
      plain("unknown_is_free", AMHA_FIELD(occupancy.unknown_is_free)),
      // The lattice refuses more (LatticeGraph's config check).
      plain("cost_penalty", AMHA_FIELD(lattice.cost.penalty), 0.0, 1e4),
      startUpOnly(plain("max_map_cells", AMHA_FIELD(max_map_cells), 1, kMaxCount)),
      choice("algorithm", AMHA_FIELD(algorithm), amha::parseAlgorithm, amha::algorithmName,
             "algorithm", "amha, mha, ara, ana, wastar, astar"),
      plain("num_inadmissible", AMHA_FIELD(lattice.heuristics.num_inadmissible), 0, 3),
      plain("grid_anchor", AMHA_FIELD(lattice.heuristics.grid_anchor)),
      plain("coarse_anchor", AMHA_FIELD(lattice.heuristics.coarse_anchor)),
      plain("coarse_block", AMHA_FIELD(lattice.heuristics.coarse_block), 0, lat::kMaxCoarseBlock),
      plain("kinematic_radius", AMHA_FIELD(lattice.heuristics.kinematic_radius), 0.0, 100.0),
      plain("anchor_connectivity", AMHA_FIELD(lattice.heuristics.anchor_connectivity), 8, 16,
            eight_or_16),
      choice("inadmissible_heuristics", AMHA_FIELD(lattice.heuristics.inadmissible),
             lat::parseInadmissible, lat::inadmissibleName, "kind of inadmissible heuristics",
             "kinematic, paper"),
      plain("anchor_turn_term", AMHA_FIELD(lattice.heuristics.anchor_turn_term)),
      plain("inflate_heading_terms", AMHA_FIELD(lattice.heuristics.inflate_heading_terms)),
      plain("displacement_grid", AMHA_FIELD(lattice.heuristics.displacement_grid)),
      plain("bidirectional_after", AMHA_FIELD(lattice.heuristics.bidirectional_after_s), -1.0,
            3600.0),
      plain("backward_search", AMHA_FIELD(lattice.backward_search)),
      plain("heuristic_cache_size", AMHA_FIELD(lattice.cache.size), 1, 64),
      plain("repair_heuristics", AMHA_FIELD(lattice.cache.repair)),
      plain("complete_heuristic_grids", AMHA_FIELD(lattice.cache.complete_grids)),
      weight("w1", AMHA_FIELD(w1), 1.0),
      weight("w2", AMHA_FIELD(w2), 1.0),
      choice("weight_schedule", AMHA_FIELD(weight_schedule), amha::parseWeightSchedule,
             amha::weightScheduleName, "schedule", "certified, decrement"),
      plain("certified_ratio", AMHA_FIELD(certified_ratio), 0.0, 0.999),
      plain("certified_split", AMHA_FIELD(certified_split), 0.0, 1.0),
      plain("final_gap", AMHA_FIELD(final_gap), 0.0, 1e3),
      plain("publish_within_iterations", AMHA_FIELD(publish_within_iterations)),
      plain("stall_expansions", AMHA_FIELD(stall_expansions), 0, kMaxCount),
      plain("stall_w1", AMHA_FIELD(stall_w1), 1.0, amha::kMaxWeight),
      plain("stall_mid_w1", AMHA_FIELD(stall_mid_w1), 1.0, amha::kMaxWeight),
      plain("stall_mid_expansions", AMHA_FIELD(stall_mid_expansions), 0, kMaxCount),
      plain("proof_anchor_only", AMHA_FIELD(proof_anchor_only)),
      weight("dw1", AMHA_FIELD(dw1), 0.0),
      weight("dw2", AMHA_FIELD(dw2), 0.0),
      choice("queue_schedule", AMHA_FIELD(queue_schedule), amha::parseSchedule, amha::scheduleName,
             "schedule", "rr, dts"),
      weight("eps", AMHA_FIELD(eps), 1.0),
      weight("eps_decrement", AMHA_FIELD(eps_decrement), 0.0),
      plain("default_time_budget", AMHA_FIELD(default_time_budget), 1e-3, kHuge),
      plain("ignore_goal_heading", AMHA_FIELD(ignore_goal_heading)),
      plain("start_tolerance", AMHA_FIELD(start_tolerance), 0.0, 1e3),
      plain("start_escape_penalty", AMHA_FIELD(start_escape_penalty), 1.0, 1e3),
      plain("smooth_path", AMHA_FIELD(smooth_path)),
      plain("max_memory_mb", AMHA_FIELD(max_memory_mb), 1.0, 1e7),
      frame("global_frame", AMHA_FIELD(global_frame)),
      frame("robot_base_frame", AMHA_FIELD(robot_base_frame)),
      plain("tf_timeout", AMHA_FIELD(tf_timeout), 0.0, 60.0),
      startUpOnly(plain("max_queued_requests", AMHA_FIELD(max_queued_requests), 0, 64)),
      // malloc's process-wide mmap threshold is set once (freed_memory.h).
      startUpOnly(plain("release_freed_memory", AMHA_FIELD(release_freed_memory))),
      plain("marker_spacing", AMHA_FIELD(marker_spacing), 0.01, 1e3),
  };
}

#undef AMHA_FIELD

}  // namespace

const std::vector<ParamSpec>& paramSpecs() {
  static const std::vector<ParamSpec> specs = makeSpecs();
  return specs;
}

std::string paramText(const ParamValue& value) {
  switch (value.index()) {
    case 0:
      return std::get<bool>(value) ? "true" : "false";
    case 1:
      return std::to_string(std::get<int>(value));
    case 2:
      return exact(std::get<double>(value));
    default:
      return std::get<std::string>(value);
  }
}

std::string setParam(const ParamSpec& spec, const ParamValue& value, PlannerParams* p) {
  const std::size_t expected = static_cast<std::size_t>(spec.type);
  ParamValue v = value;
  // An integer where a double is expected (YAML's 5 for 5.0) is that double.
  if (spec.type == Type::kDouble && v.index() == 1) v = static_cast<double>(std::get<int>(v));
  if (v.index() != expected) {
    static const char* const kinds[] = {"true or false", "an integer", "a number", "text"};
    return std::string("expected ") + kinds[expected] + ", got " + paramText(value);
  }
  if (spec.type == Type::kInt || spec.type == Type::kDouble) {
    const double d = spec.type == Type::kInt ? std::get<int>(v) : std::get<double>(v);
    if (!std::isfinite(d)) return "expected a number, got " + exact(d);
    const bool in_range = d >= spec.min && d <= spec.max;
    if (spec.minus_one_is_preset && !in_range && d != -1.0) {
      return exact(d) + " is neither -1 (the algorithm's preset) nor in [" + exact(spec.min) +
             ", " + exact(spec.max) + "]";
    }
    if (!spec.minus_one_is_preset && !in_range)
      return exact(d) + " is outside [" + exact(spec.min) + ", " + exact(spec.max) + "]";
  }
  return spec.set(v, p);
}

}  // namespace amha_planner
