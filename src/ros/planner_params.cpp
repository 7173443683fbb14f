// Parameter loading and request overrides (see planner_params.h).
#include "amha_planner/ros/planner_params.h"

#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <XmlRpcValue.h>

#include "amha_planner/ros/param_specs.h"

namespace amha_planner {

namespace {

[[noreturn]] void bad(const ros::NodeHandle& pnh, const std::string& name,
                      const std::string& problem) {
  throw std::invalid_argument("parameter " + pnh.resolveName(name) + ": " + problem);
}

double numberIn(const XmlRpc::XmlRpcValue& v, bool* ok) {
  *ok = true;
  if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) return static_cast<double>(v);
  if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) return static_cast<int>(v);
  *ok = false;
  return 0.0;
}

// A footprint given as a YAML list of [x, y] points (costmap_2d's other form, a string, is
// the footprint ParamSpec's).
std::vector<std::array<double, 2>> footprintFromList(const ros::NodeHandle& pnh,
                                                     XmlRpc::XmlRpcValue& v) {
  std::vector<std::array<double, 2>> out;
  for (int i = 0; i < v.size(); ++i) {
    XmlRpc::XmlRpcValue& pt = v[i];
    if (pt.getType() != XmlRpc::XmlRpcValue::TypeArray || pt.size() != 2) {
      bad(pnh, "footprint", "point " + std::to_string(i) + " is not an [x, y] pair");
    }
    bool okx = false, oky = false;
    const double x = numberIn(pt[0], &okx), y = numberIn(pt[1], &oky);
    if (!okx || !oky || !std::isfinite(x) || !std::isfinite(y)) {
      bad(pnh, "footprint", "point " + std::to_string(i) + " has a non-numeric coordinate");
    }
    out.push_back({x, y});
  }
  if (!out.empty() && out.size() < 3) bad(pnh, "footprint", "needs at least 3 points");
  return out;
}

// The XmlRpc value as a ParamValue; false for a type no parameter has (a list, a struct, ...).
bool toParamValue(const XmlRpc::XmlRpcValue& v, ParamValue* out) {
  switch (v.getType()) {
    case XmlRpc::XmlRpcValue::TypeBoolean:
      *out = static_cast<bool>(v);
      return true;
    case XmlRpc::XmlRpcValue::TypeInt:
      *out = static_cast<int>(v);
      return true;
    case XmlRpc::XmlRpcValue::TypeDouble:
      *out = static_cast<double>(v);
      return true;
    case XmlRpc::XmlRpcValue::TypeString:
      *out = static_cast<std::string>(v);
      return true;
    default:
      return false;
  }
}

bool validWeight(double w) { return w >= 1.0 && w <= amha::kMaxWeight; }  // NaN fails both

}  // namespace

std::string normaliseFrame(const std::string& frame) {
  return !frame.empty() && frame[0] == '/' ? frame.substr(1) : frame;
}

PlannerParams loadPlannerParams(const ros::NodeHandle& pnh) {
  PlannerParams p;
  for (const ParamSpec& spec : paramSpecs()) {
    XmlRpc::XmlRpcValue v;
    if (!pnh.getParam(spec.name, v)) continue;
    if (spec.name == "footprint" && v.getType() == XmlRpc::XmlRpcValue::TypeArray) {
      p.lattice.robot.footprint = footprintFromList(pnh, v);
      continue;
    }
    ParamValue value;
    if (!toParamValue(v, &value)) {
      bad(pnh, spec.name,
          spec.name == "footprint" ? "expected a list of [x, y] points"
                                   : "expected a single value");
    }
    const std::string problem = setParam(spec, value, &p);
    if (!problem.empty()) bad(pnh, spec.name, problem);
  }
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
    c.proof_anchor_only = params.proof_anchor_only;
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
