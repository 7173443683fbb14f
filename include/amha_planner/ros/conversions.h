// Message <-> library conversions for the ROS layer: occupancy grids to GridMaps, poses to
// Pose2D and back, lattice solutions to nav_msgs/Path and PlanSolution, footprint markers.
// No planning logic here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/Quaternion.h>
#include <map_msgs/OccupancyGridUpdate.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Path.h>
#include <ros/time.h>
#include <visualization_msgs/MarkerArray.h>

#include "amha_planner/PlanSolution.h"
#include "amha_planner/lattice/lattice_planner.h"

namespace amha_planner {

/// Builds a GridMap from an OccupancyGrid message (the origin's yaw included). Throws
/// amha::lattice::LatticeError naming the problem (data length != width * height, resolution
/// not positive/finite, non-finite or non-planar origin, more than max_cells cells).
amha::lattice::GridMap gridMapFromOccupancy(const nav_msgs::OccupancyGrid& msg,
                                            const amha::lattice::OccupancyConversion& conversion,
                                            std::size_t max_cells);

/// Converts the cells of `rect` of `msg` into `grid`, a GridMap of msg's size (e.g. a copy of
/// the GridMap of an earlier version of msg), so that only changed cells are converted again.
/// Throws amha::lattice::LatticeError if the sizes differ or `rect` leaves the map.
void convertOccupancyCells(const nav_msgs::OccupancyGrid& msg, const amha::lattice::CellRect& rect,
                           const amha::lattice::OccupancyConversion& conversion,
                           amha::lattice::GridMap* grid);
/// Writes a partial update (costmap_2d's `<topic>_updates`, as rviz reads them) into `grid`:
/// the cells of the rectangle (x, y, width, height), row by row. Throws
/// amha::lattice::LatticeError naming the problem, leaving `grid` unchanged, if the data
/// length is not width * height, the rectangle leaves the grid, or the update names a frame
/// other than the grid's.
void applyOccupancyGridUpdate(const map_msgs::OccupancyGridUpdate& update,
                              nav_msgs::OccupancyGrid* grid);

/// Checks that a pose can be used as a planar pose: finite position, finite quaternion whose
/// norm is within 1e-3 of 1 (so zero and non-normalised quaternions are refused). On failure
/// returns false and says why in *why.
bool checkPose(const geometry_msgs::Pose& pose, std::string* why);

/// The planar pose (x, y, yaw) of a pose that passed checkPose (roll and pitch are dropped).
amha::lattice::Pose2D pose2DFromPose(const geometry_msgs::Pose& pose);

geometry_msgs::Quaternion quaternionFromYaw(double yaw);

/// A map-frame pose as a stamped message (frame, stamp).
geometry_msgs::PoseStamped poseStampedFromPose2D(const amha::lattice::Pose2D& pose,
                                                 const std::string& frame, const ros::Time& stamp);

/// A path message (frame, stamp) through the given map-frame poses.
nav_msgs::Path pathFromPoses(const std::vector<amha::lattice::Pose2D>& poses,
                             const std::string& frame, const ros::Time& stamp);

/// The message for one improved solution; costs are converted to metres-equivalent.
PlanSolution planSolutionMsg(const amha::lattice::LatticeSolution& solution,
                             std::uint32_t request_id, const std::string& frame,
                             const ros::Time& stamp);

/// The message for one smoothed solution: `published` (SmoothedStream::Step::published) as path,
/// cost and bounds, `lattice` (the search's solution) as lattice_path and lattice_cost.
PlanSolution smoothedSolutionMsg(const amha::lattice::LatticeSolution& published,
                                 const amha::lattice::LatticeSolution& lattice,
                                 std::uint32_t request_id, const std::string& frame,
                                 const ros::Time& stamp);

/// Search cost units -> metres-equivalent.
inline double costInMetres(amha::Cost cost) {
  return static_cast<double>(cost) / amha::lattice::kCostUnitsPerMetre;
}

/// Markers for rviz: the footprint outline every `spacing` metres along `poses` (and at the
/// last pose), the start and goal as arrows with their footprints. The first marker deletes
/// the previous set, so the array always shows the latest path only.
visualization_msgs::MarkerArray footprintMarkers(const amha::lattice::LatticePlanner& planner,
                                                 const std::vector<amha::lattice::Pose2D>& poses,
                                                 const amha::lattice::Pose2D& start,
                                                 const amha::lattice::Pose2D& goal,
                                                 const std::string& frame, const ros::Time& stamp,
                                                 double spacing);

}  // namespace amha_planner
