// Smoothing of lattice paths that keeps every guarantee of the lattice path: the same start and
// goal poses, a footprint that is collision-free by the lattice's own swept-cell test, curvature
// at most 1/r_min while driving (turns in place and reversals stay where the lattice put them),
// headings continuous along each driving stretch, and a cost under the planner's cost model no
// higher than the lattice path's, so the path stays within the lattice path's bound of the
// optimum. ROS-free. See docs/lattice.md, "Smoothing".
#pragma once

#include <cstddef>
#include <vector>

#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/lattice/motion_primitives.h"

namespace amha {
namespace lattice {

struct SmootherOptions {
  /// Minimum turning radius of the joining curves (metres); 0: the motion model's
  /// (modelTurningRadius). Smaller than the model's is refused.
  double turning_radius = 0.0;
};

/// One stretch of a smoothed path: poses [first, last] of SmoothedPath::poses.
struct SmoothedPiece {
  std::size_t first = 0, last = 0;
  /// True: part of a curve that replaced lattice motions (a Dubins path between the lattice
  /// path's poses at two of its states). False: a lattice motion kept as it was.
  bool shortcut = false;
  bool backward = false;    ///< driven in reverse (the heading points against the motion)
  int primitive = -1;       ///< kept motions: the primitive (index into PrimitiveSet::primitives)
  double multiplier = 1.0;  ///< shortcut pieces: the largest multiplier of the motions replaced
  Cost cost = 0;            ///< its cost by the edge cost formula (see PathSmoother)
};

struct SmoothedPath {
  std::vector<Pose2D> poses;          ///< map frame; front() and back() are the input's own
  std::vector<SmoothedPiece> pieces;  ///< consecutive: each starts where the previous ends
  Cost cost = 0;                      ///< the sum of the pieces' costs, <= lattice_cost
  /// The input's cost as its cheapest motions of this lattice: at most the search's (the same
  /// poses may be one long straight move or several short ones, whose worst cells differ).
  Cost lattice_cost = 0;
  double turning_radius = 0.0;  ///< of the shortcuts (metres)
  std::size_t shortcuts = 0;    ///< how many curves replaced lattice motions
  double seconds = 0.0;         ///< time smooth() took
};

/// How a primitive moves: forward or backward when every step between its intermediate poses
/// runs along (against) the headings at both ends of the step, in place when it does not move,
/// mixed otherwise (sideways, a turn on the spot in the middle, a change of direction).
enum class MotionKind { kForward, kBackward, kInPlace, kMixed };
MotionKind motionKind(const MotionPrimitive& primitive);

/// The motion model's minimum turning radius (metres): the tightest turn of its driving
/// primitives, measured between consecutive intermediate poses as 1 / (2 sin(|dtheta| / 2) /
/// |dp|), the radius of the circle through both (exact for samples of an arc). Generated
/// primitives turn no tighter than LatticeConfig::Motion::turning_radius and usually wider (their
/// arcs must end on cell centres); an .mprim file's min_turning_radius_m is its authors' claim.
/// Infinite if no driving primitive turns (then nothing is shortcut).
double modelTurningRadius(const LatticeGraph& graph);

/// The longest motion of the primitive set (metres of intermediate-pose polyline): shortcuts
/// are costed in pieces no longer than this, so their cell-cost penalty is as local as a
/// lattice path's.
double longestPrimitiveLength(const LatticeGraph& graph);

/// Smooths lattice paths of one LatticeGraph (a LatticePlanner's graph()). Thread-safe: smooth()
/// may be called from several threads at once.
///
/// The input is split into driving stretches at turns in place, reversals and motions that
/// change direction inside; within a stretch, greedily from its start, the farthest later state
/// that a Dubins path (radius turningRadius()) reaches collision-free and no costlier than the
/// motions it replaces is joined to it (found by doubling, then bisection). The curve runs
/// between the input's own poses at the two states (a file's motions may end a little off a
/// state's centre and heading). Its poses are at most a cell apart, and it is tested exactly as
/// the lattice tests a primitive from its first state: centre cells below inscribed, swept cells
/// (primitiveCells' sweep steps) below lethal, all inside the map; cells are rasterised only
/// where the clearance classes do not prove them free (as LatticeGraph::edgeCost skips) and a
/// box around them holds a blocked cell. Its cost is that of consecutive pieces of at most
/// longestPrimitiveLength(), each by LatticeConfig's formula: round(ceil(1000 x max(L,
/// nominal_speed x total |dtheta| / omega)) x m) plus the penalty of the worst centre cell of the
/// piece, with m the largest multiplier of the motions it replaces.
class PathSmoother {
 public:
  /// Throws std::invalid_argument for a turning radius below the model's or not finite.
  explicit PathSmoother(const LatticeGraph& graph, const SmootherOptions& options = {});

  /// `lattice_path`: a path of this lattice in the map frame, as LatticeSolution::poses (the
  /// intermediate poses of each motion). Throws std::invalid_argument if it is not one (names
  /// the first pose that no valid motion explains).
  SmoothedPath smooth(const std::vector<Pose2D>& lattice_path) const;

  double turningRadius() const { return radius_; }
  /// The cost of driving through `poses` (metres and radians relative to cell (x, y)'s centre,
  /// in the grid frame, as a primitive's intermediate poses) as a shortcut of multiplier
  /// `multiplier`: the test and cost smooth() gives its shortcuts, or kInvalidEdge. For a
  /// driving primitive no longer than longestPrimitiveLength() this is LatticeGraph::edgeCost.
  Cost motionCost(int x, int y, const std::vector<Pose2D>& poses, double multiplier) const;

 private:
  struct Action {
    MotionKind motion = MotionKind::kMixed;
    double multiplier = 1.0;
  };
  struct Edge;
  struct Candidate;
  /// The input's motions; `grid` receives its poses in the grid frame (metres from the map's
  /// corner).
  std::vector<Edge> parse(const std::vector<Pose2D>& poses, std::vector<Pose2D>& grid) const;
  struct Scratch;  // buffers of one smooth() call
  bool tryShortcut(const Pose2D& from, const Pose2D& to, int x0, int y0, bool backward,
                   double radius, double multiplier, Cost budget, Candidate& out,
                   Scratch& scratch) const;
  Cost shortcutCost(int x0, int y0, const std::vector<Pose2D>& poses, double multiplier,
                    Cost budget, std::vector<SmoothedPiece>* pieces, Scratch& scratch) const;
  bool sweepFree(int x0, int y0, const std::vector<Pose2D>& poses, std::size_t first,
                 std::size_t last, Scratch& scratch) const;
  bool provablyFree(double cx, double cy, double reach) const;

  const LatticeGraph& graph_;
  double radius_ = 0.0;
  double piece_length_ = 0.0;
  double omega_ = 0.0;
  std::vector<Action> actions_;  // per LatticeGraph action: its kind and multiplier
};

/// The smoothed path as a solution: raw's with poses and search.cost the smoothed path's and
/// search.certified_bound = raw's x cost / raw cost, clamped to [1, nominal_bound] (the lattice
/// optimum's lower bound is unchanged; below 1 the path beats the lattice optimum, and 1 is
/// still a true bound). nominal_bound stays: cost <= raw cost <= nominal_bound x optimum.
LatticeSolution smoothedSolution(const LatticeSolution& raw, const SmoothedPath& smoothed);

/// Smooths the solutions of one plan() as they stream in, for publishing: each solution's
/// lattice path is smoothed (once per distinct path), and if an earlier solution's smoothed path
/// costs less it is published again instead, so the published cost never rises (a cheaper
/// lattice path may smooth less well). Bounds of a republished path: cost <= this solution's
/// smoothed cost <= its lattice cost <= its nominal bound x optimum, so its nominal bound
/// holds, and its certified bound is scaled as in smoothedSolution. Certified bounds never rise
/// either: the previous one holds for a path no costlier. Not thread-safe.
class SmoothedStream {
 public:
  explicit SmoothedStream(const PathSmoother& smoother) : smoother_(smoother) {}

  struct Step {
    LatticeSolution published;      ///< poses, cost and bounds to publish
    SmoothedPath smoothed;          ///< this solution's own smoothed path
    bool republished = false;       ///< published is an earlier solution's smoothed path
    bool same_as_previous = false;  ///< published.poses are the previous step's
  };
  /// Throws what PathSmoother::smooth throws. A path that leaves a start in collision
  /// (raw.escape_poses > 0) keeps its escape as it is; the rest is smoothed.
  const Step& add(const LatticeSolution& raw);

 private:
  SmoothedPath smoothAfterEscape(const LatticeSolution& raw) const;
  const PathSmoother& smoother_;
  Step step_;
  std::vector<StateId> last_ids_;  // of the last lattice path smoothed
  bool started_ = false;
};

}  // namespace lattice
}  // namespace amha
