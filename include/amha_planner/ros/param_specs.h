// The server's ~parameters in one list: each one's name, type, range and place in PlannerParams.
// Start-up (loadPlannerParams) and dynamic_reconfigure (configFromParams, paramsFromConfig) read
// and check parameters through it, and the tests hold cfg/AmhaPlanner.cfg, config/planner.yaml
// and docs/ros.md to it, so that a parameter is written once in code.
#pragma once

#include <functional>
#include <string>
#include <variant>
#include <vector>

#include "amha_planner/ros/planner_params.h"

namespace amha_planner {

/// A parameter's value, as XmlRpc and dynamic_reconfigure carry it.
using ParamValue = std::variant<bool, int, double, std::string>;

struct ParamSpec {
  enum class Type { kBool, kInt, kDouble, kString };
  std::string name;  ///< the ~parameter's (and the .cfg entry's) name
  Type type = Type::kDouble;
  double min = 0.0, max = 0.0;       ///< kInt, kDouble: the values accepted
  bool minus_one_is_preset = false;  ///< -1 is accepted too: "the algorithm's preset"
  bool reconfigurable = true;        ///< in cfg/AmhaPlanner.cfg; false: read at start-up only
  /// The value in `p` (PlannerParams{}: the default).
  std::function<ParamValue(const PlannerParams& p)> get;
  /// Stores a value of `type` that passed the range check into `p`: "" or why it is refused
  /// (an unknown name, a heading count that is no multiple of 8, ...).
  std::function<std::string(const ParamValue& v, PlannerParams* p)> set;
};

/// Every parameter the server reads, in config/planner.yaml's order.
const std::vector<ParamSpec>& paramSpecs();

/// Checks `value` against `spec` (its type, a finite number in range or -1 for a preset) and
/// stores it in `p`: "" or the problem, a sentence without the parameter's name.
std::string setParam(const ParamSpec& spec, const ParamValue& value, PlannerParams* p);

/// `value` as text: true/false, numbers in their shortest exact form, strings as they are.
std::string paramText(const ParamValue& value);

}  // namespace amha_planner
