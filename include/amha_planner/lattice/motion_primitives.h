// Motion primitives: SBPL .mprim files (read and write) and a generator from robot parameters.
// A primitive starts at the centre of a cell with a discrete heading and ends at the centre of
// another cell (endpose, in cells) with a discrete heading; its intermediate poses (metres,
// relative to the start cell's centre, absolute headings in radians) describe the motion.
#pragma once

#include <string>
#include <vector>

#include "amha_planner/lattice/lattice_planner.h"

namespace amha {
namespace lattice {

struct MotionPrimitive {
  int id = 0;                ///< primID (index within its start heading)
  int start_heading = 0;     ///< 0 .. num_headings - 1
  int end_dx = 0, end_dy = 0;  ///< end cell relative to the start cell
  int end_heading = 0;       ///< 0 .. num_headings - 1
  double cost_multiplier = 1.0;  ///< additionalactioncostmult (> 0)
  double turning_radius = 0.0;   ///< non-uniform files only (0: straight or turn in place;
                                 ///< SBPL's files sign it: negative turns right)
  std::vector<Pose2D> poses;     ///< intermediate poses, first at (0, 0)
};

/// A complete set of primitives for one resolution and heading discretisation.
struct PrimitiveSet {
  double resolution = 0.0;      ///< metres per cell
  int num_headings = 0;
  /// Angle of each heading in [0, 2 pi). Uniform sets: 2 pi i / N. Non-uniform sets (SBPL's
  /// "min_turning_radius_m" format, and our generator) list them explicitly.
  std::vector<double> heading_angles;
  bool uniform = true;
  double min_turning_radius = 0.0;  ///< non-uniform files' header value
  /// All primitives, grouped by start heading (heading 0 first), file order within a heading.
  std::vector<MotionPrimitive> primitives;

  /// The discrete heading nearest to `theta` (any real angle), as SBPL discretises:
  /// uniform: floor(normalize(theta + bin / 2) / bin); non-uniform: the nearest listed angle.
  int headingIndex(double theta) const;
  /// Primitives starting at heading h: [begin, end) into `primitives`.
  std::pair<std::size_t, std::size_t> range(int heading) const;
};

/// Angle in [0, 2 pi).
double normalizeAngle(double a);
/// Shortest unsigned angular distance between two angles (0 .. pi).
double angleDistance(double a, double b);

/// Reads an SBPL .mprim file, validating everything: header labels and values, the resolution
/// against `map_resolution` (if > 0), heading indices, every number, that the first
/// intermediate pose is the start cell's centre at the start heading, that the last one
/// discretises to endpose_c, and that every heading has the same number of primitives.
/// Errors are LatticeError (kPrimitives) "file:line: problem".
PrimitiveSet readMprimFile(const std::string& path, double map_resolution = 0.0);
PrimitiveSet readMprim(std::istream& in, const std::string& name, double map_resolution = 0.0);

/// Writes `set` in SBPL's format (the non-uniform variant when the headings are not uniform),
/// with 6 decimals, so readMprimFile reads it back. Throws LatticeError (kPrimitives).
void writeMprimFile(const std::string& path, const PrimitiveSet& set);
void writeMprim(std::ostream& out, const PrimitiveSet& set);

struct PrimitiveGeneratorOptions {
  double resolution = 0.05;       ///< metres per cell
  int num_headings = 16;          ///< a multiple of 8
  double turning_radius = 0.5;    ///< minimum turning radius of the arcs (m, > 0)
  bool allow_reverse = false;     ///< add backward straight moves and backward arcs
  bool turn_in_place = true;      ///< add turns on the spot to the neighbouring headings
  double long_straight_length = 0.0;  ///< length of the long straight move (m); 0: 8 cells
  double reverse_multiplier = 3.0;    ///< cost multiplier of backward motions
  double turn_in_place_multiplier = 1.0;
  double arc_multiplier = 1.0;
};

/// Generates primitives without MATLAB. Headings are the directions of small integer lattice
/// vectors (0, atan(1/2), 45 deg, ... for 16), so straight moves end exactly on cells with
/// unchanged heading: per heading a 1-step and a long straight move along its lattice vector,
/// arcs to the two neighbouring headings (a circular arc of radius >= turning_radius joined to
/// a straight segment, ending exactly on a cell centre), optionally backward moves and turns in
/// place. The set is symmetric under the 8 lattice symmetries. Throws LatticeError (kConfig).
PrimitiveSet generatePrimitives(const PrimitiveGeneratorOptions& options);

}  // namespace lattice
}  // namespace amha
