// The server's run-time parameters as a dynamic_reconfigure configuration (cfg/AmhaPlanner.cfg)
// and back, with the checks a change must pass before the server takes it.
#pragma once

#include <cstdint>
#include <string>

#include <ros/node_handle.h>

#include "amha_planner/AmhaPlannerConfig.h"
#include "amha_planner/ros/planner_params.h"

namespace amha_planner {

/// The level bits of cfg/AmhaPlanner.cfg: search parameters apply to the next request; the
/// others rebuild the planner from the current map.
constexpr std::uint32_t kReconfigureSearch = 1;
constexpr std::uint32_t kReconfigureRebuild = 2;

/// The configuration that `params` is (the footprint in costmap_2d's string form).
AmhaPlannerConfig configFromParams(const PlannerParams& params);

/// `base` with `config`'s values, checked as ~parameters are at start-up (ranges aside, which
/// dynamic_reconfigure clamps) and for what its ranges cannot say: not a number, a weight
/// between -1 and 1, an unknown algorithm or schedule, a heading count that is no multiple of 8,
/// a malformed footprint. False with a message naming the parameter (resolved in pnh).
bool paramsFromConfig(const AmhaPlannerConfig& config, const PlannerParams& base,
                      const ros::NodeHandle& pnh, PlannerParams* out, std::string* error);

/// Whether a planner can be built with params.lattice on `map` (the current map): the robot
/// must fit in it, and a build on a free map of its resolution, as large as the robot, must
/// pass (the primitives generated or read and checked against the resolution, the footprint
/// and its sweeps, the cost model). map null (no map yet): the footprint alone is checked.
/// False with the lattice's message.
bool latticeBuilds(const PlannerParams& params, const amha::lattice::GridMap* map,
                   std::string* error);

/// "name old -> new" for every parameter that differs, comma-separated (for the log).
std::string changedParameters(const AmhaPlannerConfig& from, const AmhaPlannerConfig& to);

}  // namespace amha_planner
