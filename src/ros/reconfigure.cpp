// Run-time parameters <-> dynamic_reconfigure configuration (see reconfigure.h).
#include "amha_planner/ros/reconfigure.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include <dynamic_reconfigure/Config.h>

#include "amha_planner/lattice/detail/footprint.h"
#include "amha_planner/ros/param_specs.h"

namespace amha_planner {

namespace {

namespace lat = amha::lattice;

// The entries of `msg` that hold values of v's type.
template <class Visit>
auto withEntries(dynamic_reconfigure::Config& msg, const ParamValue& v, Visit visit) {
  switch (v.index()) {
    case 0:
      return visit(msg.bools);
    case 1:
      return visit(msg.ints);
    case 2:
      return visit(msg.doubles);
    default:
      return visit(msg.strs);
  }
}

// Writes `v` into the entry `name` of `msg`; false if it has none of v's type.
bool put(dynamic_reconfigure::Config& msg, const std::string& name, const ParamValue& v) {
  return withEntries(msg, v, [&](auto& entries) {
    for (auto& e : entries) {
      if (e.name != name) continue;
      using T = std::decay_t<decltype(e.value)>;
      if constexpr (std::is_same_v<T, std::string>) {
        e.value = std::get<std::string>(v);
      } else if constexpr (std::is_same_v<T, double>) {
        e.value = std::get<double>(v);
      } else if constexpr (std::is_same_v<T, std::int32_t>) {
        e.value = std::get<int>(v);
      } else {  // a message's bool
        e.value = std::get<bool>(v);
      }
      return true;
    }
    return false;
  });
}

// The entry `name` of `msg`, of the type `like` has; false if there is none.
bool take(dynamic_reconfigure::Config& msg, const std::string& name, ParamValue* like) {
  return withEntries(msg, *like, [&](auto& entries) {
    for (const auto& e : entries) {
      if (e.name != name) continue;
      using T = std::decay_t<decltype(e.value)>;
      if constexpr (std::is_same_v<T, std::string> || std::is_same_v<T, double>) {
        *like = e.value;
      } else if constexpr (std::is_same_v<T, std::int32_t>) {
        *like = static_cast<int>(e.value);
      } else {  // a message's bool
        *like = e.value != 0;
      }
      return true;
    }
    return false;
  });
}

}  // namespace

AmhaPlannerConfig configFromParams(const PlannerParams& p) {
  AmhaPlannerConfig c = AmhaPlannerConfig::__getDefault__();
  dynamic_reconfigure::Config msg;
  c.__toMessage__(msg);
  // paramSpecs() and cfg/AmhaPlanner.cfg name the same parameters (param_specs_test.cpp).
  for (const ParamSpec& spec : paramSpecs()) {
    if (spec.reconfigurable) put(msg, spec.name, spec.get(p));
  }
  c.__fromMessage__(msg);
  return c;
}

bool paramsFromConfig(const AmhaPlannerConfig& c, const PlannerParams& base,
                      const ros::NodeHandle& pnh, PlannerParams* out, std::string* error) {
  auto fail = [&](const std::string& name, const std::string& problem) {
    *error = "parameter " + pnh.resolveName(name) + ": " + problem;
    return false;
  };
  dynamic_reconfigure::Config msg;
  c.__toMessage__(msg);
  // Checked as at start-up: dynamic_reconfigure clamps numbers into the .cfg's ranges (the
  // specs' own), but a NaN passes every comparison, and names and footprints it cannot check.
  PlannerParams p = base;
  for (const ParamSpec& spec : paramSpecs()) {
    if (!spec.reconfigurable) continue;
    ParamValue v = spec.get(base);
    if (!take(msg, spec.name, &v)) return fail(spec.name, "missing from the configuration");
    const std::string problem = setParam(spec, v, &p);
    if (!problem.empty()) return fail(spec.name, problem);
  }
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
  each(a.bools, b.bools, [](bool v) { return paramText(v); });
  each(a.ints, b.ints, [](int v) { return paramText(v); });
  each(a.doubles, b.doubles, [](double v) { return paramText(v); });
  each(a.strs, b.strs, [](const std::string& v) { return "'" + v + "'"; });
  return s.str();
}

}  // namespace amha_planner
