// Shared by the primitive generators and readers: the lattice's heading directions, paths of
// straight and circular pieces sampled into poses, and the lattice's 8 symmetries.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "amha_planner/lattice/motion_primitives.h"

namespace amha {
namespace lattice {
namespace detail {

struct Vec {
  int x, y;
};

/// A primitive's path may be at most this many cells long: everything built from it (its cells,
/// the footprint's sweep) grows with its length. Real ones are a few cells to a few dozen (SBPL's
/// longest is 8; a 10 m turning radius at 0.05 m gives 80-cell arcs).
constexpr double kMaxPrimitiveCells = 1000.0;

/// The length of the polyline through `poses` (their units).
double polylineLength(const std::vector<Pose2D>& poses);

/// The N lattice directions (N a multiple of 8), counter-clockwise from (1, 0): per octant the
/// smallest integer vectors nearest to uniform spacing, mirrored and rotated to the others.
/// Throws LatticeError (kConfig) when no such vectors exist.
std::vector<Vec> headingVectors(int n);

/// Throws LatticeError (kConfig) "primitive generator: <what>".
[[noreturn]] void generatorError(const std::string& what);

/// The index of direction v (any multiple of a heading's vector) in `dirs`; LatticeError if none.
int directionIndex(const std::vector<Vec>& dirs, Vec v);

/// Throws LatticeError (kConfig) unless the options both generators share are valid.
void validateGeneratorOptions(const PrimitiveGeneratorOptions& o);

/// An empty set for the options: resolution, the headings of `dirs`, the turning radius and
/// the motion model's Nav2 name.
PrimitiveSet latticeSet(const PrimitiveGeneratorOptions& o, const std::vector<Vec>& dirs);

/// A planar path piece: a straight (curvature 0) or a circular arc.
struct Piece {
  double length;     ///< metres
  double curvature;  ///< signed, 1/m: positive turns left
};

/// Poses along `pieces` from the origin at travel direction theta0, evenly spaced at most
/// `spacing` apart (at least 3), first and last included; pose_offset is added to every pose's
/// angle (pi for backward motion, whose heading is opposite to its travel direction).
std::vector<Pose2D> samplePath(double theta0, const std::vector<Piece>& pieces, double spacing,
                               double pose_offset);

/// A lattice symmetry: an optional x <-> y reflection, then `quarter` quarter turns.
struct Symmetry {
  bool reflect;
  int quarter;
  Vec apply(Vec v) const;
  Pose2D apply(const Pose2D& p) const;
};

/// A turn on the spot from heading h to its neighbour h + side (side = +1 or -1), 5 poses.
MotionPrimitive turnOnTheSpot(const PrimitiveSet& set, int h, int side, double multiplier);

/// `p`, a primitive of a base heading, under symmetry g, starting at heading `start` (g's image
/// of p's start): end cell and heading mapped, poses mapped with the ends snapped exactly to the
/// lattice states, angles in [0, 2 pi); a reflection changes the sign of the turning radius.
MotionPrimitive transformed(const MotionPrimitive& p, const Symmetry& g, int start,
                            const std::vector<Vec>& dirs, const PrimitiveSet& set);

/// Groups set.primitives by start heading (stable) and numbers them 0, 1, ... per heading.
void numberByHeading(PrimitiveSet& set);

/// Drops exact copies of a primitive within a heading (SBPL files are padded with them, since
/// SBPL needs the same count per heading): they would only make the search try a move twice.
/// Keeps the set grouped by heading and the remaining primitives' ids.
void dropCopies(PrimitiveSet& set);

}  // namespace detail
}  // namespace lattice
}  // namespace amha
