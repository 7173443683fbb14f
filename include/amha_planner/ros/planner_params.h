// The planning server's parameters (private ~ names, see config/planner.yaml and docs/ros.md)
// and how a request's optional overrides combine with them.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <ros/node_handle.h>

#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/search/planner.h"

namespace amha_planner {

/// Ranges of ~robot_radius and ~turning_radius (metres).
constexpr double kMaxRobotRadius = 10.0;
constexpr double kMaxTurningRadius = 100.0;

struct PlannerParams {
  amha::lattice::LatticeConfig lattice;              ///< robot and motion model
  amha::lattice::OccupancyConversion occupancy;      ///< how the map's cells become costs
  std::size_t max_map_cells = std::size_t{1} << 24;  ///< bigger maps are refused

  amha::Algorithm algorithm = amha::Algorithm::kAmhaStar;
  /// Per-algorithm weights: A-MHA*/MHA* use w1, w2, dw1, dw2; ARA* uses eps and
  /// eps_decrement; weighted A* uses eps. A value < 0 means "the algorithm's preset".
  double w1 = -1, w2 = -1, dw1 = -1, dw2 = -1, eps = -1, eps_decrement = -1;
  /// A-MHA*/MHA*: which inadmissible queue goes next (round robin, as in the paper, or DTS).
  amha::QueueSchedule queue_schedule = amha::QueueSchedule::kRoundRobin;
  /// A-MHA*: how the weights fall between iterations and whether improvements are published
  /// within them (PlannerConfig's fields; the defaults are lattice::defaultPlannerConfig's).
  amha::WeightSchedule weight_schedule =
      amha::lattice::defaultPlannerConfig(amha::Algorithm::kAmhaStar).weight_schedule;
  double certified_ratio =
      amha::lattice::defaultPlannerConfig(amha::Algorithm::kAmhaStar).certified_ratio;
  double certified_split =
      amha::lattice::defaultPlannerConfig(amha::Algorithm::kAmhaStar).certified_split;
  double final_gap = amha::lattice::defaultPlannerConfig(amha::Algorithm::kAmhaStar).final_gap;
  bool publish_within_iterations =
      amha::lattice::defaultPlannerConfig(amha::Algorithm::kAmhaStar).publish_within_iterations;
  int stall_expansions = static_cast<int>(
      amha::lattice::defaultPlannerConfig(amha::Algorithm::kAmhaStar).stall_expansions);
  double stall_w1 = amha::lattice::defaultPlannerConfig(amha::Algorithm::kAmhaStar).stall_w1;
  double stall_mid_w1 =
      amha::lattice::defaultPlannerConfig(amha::Algorithm::kAmhaStar).stall_mid_w1;
  int stall_mid_expansions = static_cast<int>(
      amha::lattice::defaultPlannerConfig(amha::Algorithm::kAmhaStar).stall_mid_expansions);
  bool proof_anchor_only =
      amha::lattice::defaultPlannerConfig(amha::Algorithm::kAmhaStar).proof_anchor_only;

  double default_time_budget = 5.0;  ///< seconds, when a request gives 0
  /// Publish smoothed paths (PathSmoother): PlanSolution::path smoothed, lattice_path the raw.
  bool smooth_path = true;
  /// Every request's goal heading is free (as if each set ignore_goal_heading; also
  /// ~make_plan's, whose GetPlan cannot say it).
  bool ignore_goal_heading = false;
  double max_memory_mb = 2048.0;  ///< search + lattice state memory cap per request
  /// A start in collision may be left within this many metres (a request's start_tolerance
  /// of 0 takes it; 0: refused), each escape motion at this penalty (StartOptions).
  double start_tolerance = 0.0;
  double start_escape_penalty = 2.0;

  std::string global_frame = "map";
  std::string robot_base_frame = "base_link";
  double tf_timeout = 0.5;  ///< seconds to wait for a transform

  int max_queued_requests = 2;  ///< requests that may wait while one plans; more: BUSY
  /// Returns the memory of replaced maps and finished requests to the system: blocks of 4 MiB
  /// and more are mapped alone (process-wide, freed_memory.h), and the heap's free pages are
  /// trimmed after much has been freed. Off: glibc's defaults, which keep tens of MB of a
  /// replaced 4000 x 4000 map resident for reuse. Read at start-up only (not reconfigurable).
  bool release_freed_memory = true;
  double marker_spacing = 0.5;  ///< metres between footprint markers along the path
};

/// The parameters in force, shared by the server's threads: a reconfiguration replaces them
/// whole, and each reader takes a snapshot.
class ParamsInForce {
 public:
  explicit ParamsInForce(const PlannerParams& params)
      : params_(std::make_shared<const PlannerParams>(params)) {}
  std::shared_ptr<const PlannerParams> get() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return params_;
  }
  void set(std::shared_ptr<const PlannerParams> params) {
    std::lock_guard<std::mutex> lock(mutex_);
    params_ = std::move(params);
  }

 private:
  mutable std::mutex mutex_;
  std::shared_ptr<const PlannerParams> params_;
};

/// Reads the parameters under `pnh` (a private node handle). Throws std::invalid_argument
/// naming the parameter and the problem for a value of the wrong type or range.
PlannerParams loadPlannerParams(const ros::NodeHandle& pnh);

/// The search configuration for a request: `algorithm_name` "" keeps the configured algorithm;
/// w1/w2 of 0 keep the configured weights (for ara and wastar, w1 is epsilon and w2 is unused).
/// Returns false with a message for an unknown name or weights outside [1, amha::kMaxWeight]
/// (NaN and infinities included).
bool searchConfigFor(const PlannerParams& params, const std::string& algorithm_name, double w1,
                     double w2, amha::PlannerConfig* out, std::string* error);

/// Strips a leading '/' (tf2 frame ids have none).
std::string normaliseFrame(const std::string& frame);

}  // namespace amha_planner
