// The robot's footprint and the cells it covers: exact polygon rasterisation (a cell counts when
// its closed square meets the closed polygon) and the cells swept along a primitive.
#pragma once

#include <array>
#include <vector>

#include "amha_planner/lattice/lattice_config.h"

namespace amha {
namespace lattice {

struct CellOffset {
  int dx = 0, dy = 0;
  bool operator==(const CellOffset& o) const { return dx == o.dx && dy == o.dy; }
  bool operator<(const CellOffset& o) const { return dy < o.dy || (dy == o.dy && dx < o.dx); }
};

/// A point in "cell units": cell (i, j) is the square [i, i + 1] x [j, j + 1].
struct CellPoint {
  double x = 0.0, y = 0.0;
};

/// Tolerance (cells) by which cell squares are grown, so that a boundary running exactly along a
/// grid line or through a corner marks the cells on both sides regardless of rounding.
constexpr double kRasterEpsilon = 1e-6;

/// Appends (unsorted, possibly repeated) the cells whose square, grown by kRasterEpsilon, meets
/// the segment p-q.
void rasterizeSegment(CellPoint p, CellPoint q, std::vector<CellOffset>& out);
/// Appends the cells meeting the closed polygon (boundary via rasterizeSegment, interior via the
/// cells whose centre is inside, even-odd rule).
void rasterizePolygon(const std::vector<CellPoint>& polygon, std::vector<CellOffset>& out);
void rasterizePolygon(const CellPoint* polygon, std::size_t size, std::vector<CellOffset>& out);
/// Sorts and removes duplicates.
void uniqueCells(std::vector<CellOffset>& cells);

/// The robot's outline. A polygon (metres, base frame, x forward) or, for a round robot, a
/// 16-gon circumscribing the circle; an empty polygon is a point robot (radius 0).
struct RobotFootprint {
  std::vector<std::array<double, 2>> polygon;
  double inscribed_radius = 0.0;      ///< largest circle about the origin inside the polygon
  double circumscribed_radius = 0.0;  ///< smallest circle about the origin containing it

  /// From LatticeConfig::Robot (footprint, or radius). Throws LatticeError (kRobot) for fewer than
  /// 3 vertices, non-finite values, zero area, a self-intersecting polygon or a bad radius.
  static RobotFootprint fromConfig(const LatticeConfig& config);

  /// The polygon placed at `pose` (same units as the pose).
  std::vector<std::array<double, 2>> at(const Pose2D& pose) const;

  /// Throws LatticeError (kRobot) if the inscribed circle is wider than a map of width x height
  /// cells of `resolution` m: no pose on it is collision-free.
  void checkFitsMap(int width, int height, double resolution) const;
};

/// The cells a primitive touches, relative to its start cell.
struct PrimitiveCells {
  /// Cells the robot's centre crosses: those meeting the polyline of intermediate positions.
  std::vector<CellOffset> centre;
  /// Cells the footprint sweeps: the footprint at the first pose, plus every cell the
  /// footprint's edges sweep between densely interpolated poses (positions linear, headings
  /// along the shorter arc, so that no vertex moves more than a quarter cell between samples).
  /// For a translation this is exactly the swept area; empty for a point robot.
  std::vector<CellOffset> swept;
};

/// `poses` are relative to the start cell's centre (metres, absolute headings).
PrimitiveCells primitiveCells(const RobotFootprint& footprint, const std::vector<Pose2D>& poses,
                              double resolution);

// The steps of primitiveCells' sweep, for checking other motions (a smoothed path's) by the
// same test: between consecutive poses a and b the footprint is placed at sweepSample(a, b, s,
// n) for s = 1..n, n = sweepSteps(a, b), and each edge's quadrilateral between two consecutive
// placements is rasterised (rasterizeEdgeSweep).

/// Into how many steps the motion a -> b is cut: no footprint vertex moves more than a quarter
/// cell in one (positions linear, heading along the shorter arc).
int sweepSteps(const RobotFootprint& footprint, const Pose2D& a, const Pose2D& b,
               double resolution);
/// The pose after step s of n from a to b (s = n is b, up to rounding).
Pose2D sweepSample(const Pose2D& a, const Pose2D& b, int s, int n);
/// The footprint at `pose` (metres, relative to a cell's centre) in cell units of that cell
/// (which is the square [0, 1] x [0, 1]); `out` is overwritten.
void footprintInCells(const RobotFootprint& footprint, const Pose2D& pose, double resolution,
                      std::vector<CellPoint>& out);
/// The same with cos(pose.theta) and sin(pose.theta) given (placements at one heading).
void footprintInCells(const RobotFootprint& footprint, const Pose2D& pose, double resolution,
                      std::vector<CellPoint>& out, double cos_theta, double sin_theta);
/// Appends the cells the edges of the footprint sweep from placement `from` to `to` (both from
/// footprintInCells): for each edge, the quadrilateral between its two positions (exact for a
/// translation).
void rasterizeEdgeSweep(const std::vector<CellPoint>& from, const std::vector<CellPoint>& to,
                        std::vector<CellOffset>& out);
/// The same for edge `edge` (from vertex edge to edge + 1) alone.
void rasterizeEdgeSweep(const std::vector<CellPoint>& from, const std::vector<CellPoint>& to,
                        std::size_t edge, std::vector<CellOffset>& out);

/// Cells under the footprint at a pose relative to a cell centre (the centre cell included).
std::vector<CellOffset> footprintCells(const RobotFootprint& footprint, const Pose2D& pose,
                                       double resolution);

}  // namespace lattice
}  // namespace amha
