// Motion primitives: SBPL .mprim and Nav2 lattice (.json) files, read and written, and two
// generators from robot parameters (a near-minimal control set, and the first, legacy one).
// A primitive starts at the centre of a cell with a discrete heading and ends at the centre of
// another cell (endpose, in cells) with a discrete heading; its intermediate poses (metres,
// relative to the start cell's centre, absolute headings in radians) describe the motion.
#pragma once

#include <string>
#include <vector>

#include "amha_planner/lattice/lattice_config.h"

namespace amha {
namespace lattice {

struct MotionPrimitive {
  int id = 0;                    ///< primID (index within its start heading)
  int start_heading = 0;         ///< 0 .. num_headings - 1
  int end_dx = 0, end_dy = 0;    ///< end cell relative to the start cell
  int end_heading = 0;           ///< 0 .. num_headings - 1
  double cost_multiplier = 1.0;  ///< additionalactioncostmult (> 0)
  double turning_radius = 0.0;   ///< non-uniform files only (0: straight or turn in place;
                                 ///< SBPL's files sign it: negative turns right)
  std::vector<Pose2D> poses;     ///< intermediate poses, first at (0, 0)
  // ---- Added with Nav2's files (defaults: a forward motion of unknown shape). ----
  /// Lengths of the circular and the straight parts (m), as Nav2's files give them; the
  /// generators and the Nav2 reader fill them, the .mprim reader estimates them from the poses.
  double arc_length = 0.0, straight_length = 0.0;
  bool reverse = false;  ///< drives backwards (a backward twin of a forward motion)
};

/// A complete set of primitives for one resolution and heading discretisation.
struct PrimitiveSet {
  double resolution = 0.0;  ///< metres per cell
  int num_headings = 0;
  /// Angle of each heading in [0, 2 pi). Uniform sets: 2 pi i / N. Non-uniform sets (SBPL's
  /// "min_turning_radius_m" format, and our generator) list them explicitly.
  std::vector<double> heading_angles;
  bool uniform = true;
  double min_turning_radius = 0.0;  ///< non-uniform files' header value
  /// Nav2's motion_model ("ackermann", "diff", "omni"), for Nav2 files and generated sets;
  /// empty for .mprim files (added with Nav2's files).
  std::string motion_model;
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
/// discretises to endpose_c, and that every heading has the same number of primitives. Exact
/// copies of a primitive (the writer's padding) are dropped after validation.
/// Errors are LatticeError (kPrimitives) "file:line: problem".
PrimitiveSet readMprimFile(const std::string& path, double map_resolution = 0.0);
PrimitiveSet readMprim(std::istream& in, const std::string& name, double map_resolution = 0.0);

/// Writes `set` in SBPL's format (the non-uniform variant when the headings are not uniform),
/// with 6 decimals, so readMprimFile reads it back. SBPL needs the same number of primitives
/// per heading: headings with fewer are padded with copies of their first primitive (new
/// primIDs), which the reader drops again. Throws LatticeError (kPrimitives).
void writeMprimFile(const std::string& path, const PrimitiveSet& set);
void writeMprim(std::ostream& out, const PrimitiveSet& set);

struct PrimitiveGeneratorOptions {
  double resolution = 0.05;           ///< metres per cell
  int num_headings = 16;              ///< a multiple of 8
  double turning_radius = 0.5;        ///< minimum turning radius of the arcs (m, > 0)
  bool allow_reverse = false;         ///< add backward motions
  bool turn_in_place = true;          ///< add turns on the spot to the neighbouring headings
  double long_straight_length = 0.0;  ///< legacy: length of the long straight move (m); 0: 8 cells
  double reverse_multiplier = 3.0;    ///< cost multiplier of backward motions
  double turn_in_place_multiplier = 1.0;
  double arc_multiplier = 1.0;  ///< legacy only
  // ---- Added with the near-minimal generator. ----
  PrimitiveGenerator generator = PrimitiveGenerator::kNearMinimal;
  /// kAckermann has no turns on the spot whatever turn_in_place says; kOmni adds sideways moves.
  MotionModel motion_model = MotionModel::kDifferential;
  /// Near-minimal: a candidate is dropped when shorter primitives already reach its end state
  /// at most (1 + tolerance) times its length (0: only exact compositions are dropped).
  double tolerance = 0.2;
  /// Near-minimal: ... and a turn is also dropped when they reach, as cheaply, a state of its
  /// end heading this many cells (Chebyshev) from its end (0: only its end state).
  int end_tolerance = 2;
};

/// The options LatticeGraph generates with for `config` at `resolution`.
PrimitiveGeneratorOptions generatorOptionsFor(const LatticeConfig& config, double resolution);

/// Generates primitives with options.generator (one of the two below). Throws LatticeError
/// (kConfig) for bad options.
PrimitiveSet generatePrimitives(const PrimitiveGeneratorOptions& options);

/// The first generator (PrimitiveGenerator::kLegacy). Headings are the directions of small
/// integer lattice vectors (0, atan(1/2), 45 deg, ... for 16), so straight moves end exactly on
/// cells with unchanged heading: per heading a 1-step and a long straight move along its lattice
/// vector, arcs to the two neighbouring headings (a circular arc of radius >= turning_radius
/// joined to a straight segment, ending exactly on a cell centre), optionally backward moves
/// and turns in place. The set is symmetric under the 8 lattice symmetries.
PrimitiveSet generateLegacyPrimitives(const PrimitiveGeneratorOptions& options);

/// A near-minimal control set (Pivtoraiko & Kelly, "Generating near minimal spanning control
/// sets for constrained motion planning in discrete state spaces", 2005), on the same headings:
/// candidates are the straight moves along each heading's lattice vector and, to every heading
/// at most 90 degrees away, the curve "straight, arc, straight" (one straight empty) that ends
/// exactly on each cell centre with an arc of radius >= turning_radius. In order of length, a
/// candidate is kept unless the primitives kept so far (with all their symmetric images)
/// already reach its end state within (1 + tolerance) times its length; it stops once several
/// cells' worth of longer candidates add nothing. Kept candidates are mapped to every heading by
/// the lattice's 8 symmetries (exact end poses), then the motion model's turns on the spot and
/// sideways moves, and backward twins if asked, are added. Poses are at most half a cell apart.
PrimitiveSet generateNearMinimalPrimitives(const PrimitiveGeneratorOptions& options);

/// Adds to `set` a backward twin of every forward motion (not turns on the spot, sideways or
/// backward moves): the robot drives the same curve backwards, so the twin of a primitive of
/// heading h + pi starts at heading h; its cost multiplier is `multiplier` times the original's.
/// Throws LatticeError (kPrimitives) when a heading has no opposite heading in the set.
void addBackwardTwins(PrimitiveSet& set, double multiplier);

// ---------------------------------------------------------------------------------------------
// Nav2 lattice primitive files (nav2_smac_planner's lattice_primitives generator output).

/// Reads a Nav2 lattice file (JSON): lattice_metadata (motion_model, turning_radius,
/// grid_resolution, num_of_headings, heading_angles, number_of_trajectories) and primitives
/// (trajectory_id, start_angle_index, end_angle_index, left_turn, trajectory_radius,
/// trajectory_length, arc_length, straight_length, poses), every field Nav2's reader requires,
/// validated: types, ranges, the resolution against `map_resolution` (if > 0), increasing
/// heading angles in [0, 2 pi), that each primitive ends on a cell centre at its end heading,
/// that every heading has primitives. Poses are stored with the start pose (0, 0, start angle)
/// first, as in .mprim sets (Nav2's files leave it out). Errors are LatticeError (kPrimitives)
/// "file: primitives[k] (trajectory_id i): field: problem" (or "file:line:column" for JSON
/// syntax errors).
PrimitiveSet readNav2LatticeFile(const std::string& path, double map_resolution = 0.0);
PrimitiveSet readNav2Lattice(std::istream& in, const std::string& name,
                             double map_resolution = 0.0);

/// Writes `set` as a Nav2 lattice file that Nav2's reader and readNav2Lattice read. Backward
/// motions are left out (Nav2 adds them itself with allow_reverse_expansion; so does
/// LatticeConfig::Motion::allow_reverse with a .json file). Throws LatticeError (kPrimitives).
void writeNav2LatticeFile(const std::string& path, const PrimitiveSet& set);
void writeNav2Lattice(std::ostream& out, const PrimitiveSet& set);

/// By extension: ".json" is a Nav2 lattice file, anything else SBPL .mprim.
bool isNav2LatticePath(const std::string& path);
PrimitiveSet readPrimitiveFile(const std::string& path, double map_resolution = 0.0);
void writePrimitiveFile(const std::string& path, const PrimitiveSet& set);

/// The primitives LatticeGraph uses for `config` on a map of `resolution`: the file (with
/// backward twins for a .json file with allow_reverse) or a generated set.
PrimitiveSet primitivesFor(const LatticeConfig& config, double resolution);

/// "diff" (or "differential"), "ackermann", "omni" -> MotionModel; false for anything else.
bool parseMotionModel(const std::string& text, MotionModel* model);
/// Nav2's names: "diff", "ackermann", "omni".
const char* motionModelName(MotionModel model);
/// "near-minimal", "legacy" -> PrimitiveGenerator; false for anything else.
bool parsePrimitiveGenerator(const std::string& text, PrimitiveGenerator* generator);
/// "near-minimal", "legacy".
const char* primitiveGeneratorName(PrimitiveGenerator generator);

}  // namespace lattice
}  // namespace amha
