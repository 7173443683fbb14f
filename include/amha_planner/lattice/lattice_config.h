// How a lattice planner is configured: the robot, its motions, what edges cost, the
// heuristics, and the heuristic cache (LatticeConfig), with the limits the planner enforces.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "amha_planner/lattice/map_types.h"

namespace amha {
namespace lattice {

/// Largest LatticeConfig::Heuristics::coarse_block: the abstraction's edges cost coarse_block^2
/// work per action to build (about a second at 1024 with 16 headings).
constexpr int kMaxCoarseBlock = 1024;
/// Smallest turning radius (in cells of the map) the primitive generator is given: far below it an
/// arc degenerates (its curvature overflows), and every radius under a cell gives the same
/// primitives anyway (the tightest turn ends on a neighbouring cell).
constexpr double kMinTurningRadiusCells = 0.01;
/// Most cells the robot's footprint may sweep along all the primitives together, as bounded
/// before any is rasterised (each costs 16 bytes of precomputed offsets and ~0.5 us to
/// rasterise): 4.2 M cells, e.g. a robot of 1.5 m radius on 2.5 cm cells takes ~1.2 M. Larger
/// robots are refused (LatticeError kRobot) instead of taking minutes and gigabytes.
constexpr std::size_t kMaxSweptCells = std::size_t{1} << 22;

/// How the robot may move, for generated primitives: a
/// differential drive also turns on the spot, an Ackermann vehicle never does, an
/// omnidirectional robot also turns on the spot and slides sideways (Nav2's "diff", "ackermann"
/// and "omni").
enum class MotionModel { kDifferential, kAckermann, kOmni };

/// Which generator makes the primitives when no file is given.
enum class PrimitiveGenerator {
  kNearMinimal,  ///< a near-minimal control set (Pivtoraiko & Kelly; motion_primitives.h)
  kLegacy,       ///< the first generator: arcs to the neighbouring headings only
};

/// The robot, its motions, what edges cost, the heuristics and their cache.
struct LatticeConfig {
  /// The robot's shape.
  struct Robot {
    std::vector<std::array<double, 2>> footprint;  ///< polygon (m, base frame); empty: a circle
    double radius = 0.2;                           ///< used when footprint is empty
  };
  /// How it moves: a primitive file, or the generator's options.
  struct Motion {
    /// Primitive file, by extension: a Nav2 lattice file (.json) or an SBPL .mprim file (any
    /// other); empty: generate primitives from the options below.
    std::string mprim_file;
    int num_headings = 16;        ///< generated primitives: a multiple of 8
    double turning_radius = 0.5;  ///< generated primitives: minimum turning radius (m)
    /// Add backward motions, costed CostModel::reverse_multiplier times their forward twins; with a
    /// Nav2 file (.json, which has forward motions only) it adds them too, as Smac's
    /// allow_reverse_expansion does.
    bool allow_reverse = false;
    /// Generated primitives: add turns on the spot (false also keeps kDifferential and kOmni
    /// from turning on the spot).
    bool turn_in_place = true;
    PrimitiveGenerator generator = PrimitiveGenerator::kNearMinimal;  ///< generated primitives
    MotionModel model = MotionModel::kDifferential;                   ///< generated primitives
  };
  /// What an edge costs: length x primitive multiplier x (1 + penalty x worst cell cost / 252).
  /// Precisely (integers, kCostUnitsPerMetre units): base = round(ceil(kCostUnitsPerMetre x
  /// max(L, nominal_speed x |dtheta| / omega)) x multiplier), where L is the length of the
  /// primitive's intermediate-pose polyline, dtheta its heading change and omega =
  /// (pi / 4) / time_to_turn_45 (so turning in place is costed by time, as in SBPL); then
  /// cost = base + ceil(base x Q[c] / 65536) with Q[c] = ceil(65536 x penalty x c / 252)
  /// and c the worst cost of the cells the robot's centre crosses. penalty = 252 gives
  /// SBPL's cost x (c + 1). See docs/lattice.md.
  struct CostModel {
    double penalty = 1.0;
    /// Robot speed (m/s) and the time to turn 45 degrees in place (s): SBPL's nominalvel and
    /// timetoturn45degsinplace (these defaults are sbpl_lattice_planner's). They only matter
    /// through the turning-time term above.
    double nominal_speed = 0.4;
    double time_to_turn_45 = 0.6;
    double reverse_multiplier = 3.0;  ///< backward motions cost this times their forward twins
  };
  /// How the inadmissible heuristics are made (kinematic_table.h for the table):
  ///  - kKinematic: each is the larger of its Dijkstra and the anchor's kinematic table, as Nav2's
  ///    Smac combines its obstacle and distance heuristics; the point robot's Dijkstra is the
  ///    anchor's grid at full Euclidean scale (no extra Dijkstra);
  ///  - kPaper: the paper's 8-connected Dijkstras alone, at the Euclidean scale.
  enum class Inadmissible { kKinematic, kPaper };
  /// The kinematic table covers at most this many cells of radius (20 m at 5 cm, 10 m at 2.5 cm).
  static constexpr int kMaxKinematicCells = 400;
  /// The heuristics: the admissible anchor's terms and the inadmissible ones.
  struct Heuristics {
    /// Inadmissible heuristics (0..3): a Dijkstra for a point robot, then Dijkstras on maps with
    /// passages narrower than the inscribed / circumscribed diameter blocked (the paper's three).
    int num_inadmissible = 3;
    Inadmissible inadmissible = Inadmissible::kKinematic;
    /// Anchor: true = max(Euclidean, an admissible cost-aware grid Dijkstra whose step costs are
    /// scaled so it is a relaxation of the lattice); false = the Euclidean distance alone (the
    /// paper's anchor). Both are admissible and consistent.
    bool grid_anchor = true;
    /// Moves of the anchor's grid: 8 (the neighbours) or 16 (also the knight moves, whose
    /// directions are those of the usual 16-heading lattices: the grid's scale, and so its
    /// distances, then fall less short of the lattice's; see docs/lattice.md).
    int anchor_connectivity = 16;
    /// The grid's step costs: one scale per class of move (axis, diagonal, knight), each as
    /// large as the primitives allow (true), or one scale for all, the largest that fits every
    /// primitive (false: its worst fit then shortens every move). Both are admissible and
    /// consistent; see LatticeGraph::computeAnchorScales.
    bool anchor_move_scales = true;
    /// With grid_anchor: also take the exact cost-to-go on a block abstraction of the lattice
    /// (cells grouped into coarse_block x coarse_block blocks; 0 = automatic: at most ~250k
    /// abstract states, see coarse_lattice.h), which knows what turning costs. Admissible and
    /// consistent.
    bool coarse_anchor = true;
    int coarse_block = 0;
    /// With grid_anchor: also take the obstacle-free kinematic cost-to-go (the exact cost of
    /// the cheapest primitive sequence on an empty map, kinematic_table.h) within this radius
    /// of the goal, in metres (0: off). Admissible and consistent; the tables are built once
    /// per primitive set and shared by every query and map.
    double kinematic_radius = 10.0;
    /// Add to the Euclidean and grid parts of the anchor a turning term: the cheapest cost of
    /// turning to the goal's heading (admissible and consistent either way). Off by default:
    /// under an inflation weight it draws the search towards states that face the goal's
    /// heading everywhere on the map, which on large maps with cheap turns costs up to 30x more
    /// expansions, and where turns are expensive (SBPL's cubicle: 20 s per 45 degrees) the
    /// block abstraction already knows their cost (docs/results/lattice.md, 1b).
    bool anchor_turn_term = false;
    /// With grid_anchor: also take the displacement grid (displacement_grid.h), a 2-D
    /// cost-to-go whose moves are the primitives' own displacements, exact in scale where the
    /// 16-connected grid must be scaled down. A helper thread computes it from the first path on
    /// (none on a single core), and the search takes it up once complete: it speeds up long
    /// proofs (the median one 1.26 times on Willow Garage at 2.5 cm) and slows short ones, which
    /// end before it is complete (the median one 3-6 % at 5 cm). Off by default for that
    /// (docs/results/smac.md, "The displacement grid"). Admissible and consistent.
    bool displacement_grid = false;
    /// A bidirectional proof (backward_bound.h): once a forward search has run this many
    /// seconds, a helper thread (none on a single core) searches backward from the goal with
    /// its own grids from the start, and its progress raises the forward anchor (admissible
    /// and consistent). Negative (the default) or NaN: never. It pays on proofs that must turn
    /// in little room, 1.5-3.8 times sooner on Willow Garage at 2.5 cm, and costs up to ~10 %
    /// elsewhere and the backward side's memory (grids, a kinematic table from the start, its
    /// states): docs/results/smac.md, "What would prove within 3x at 2.5 cm". Not with a goal
    /// of any heading, a start left by an escape, or backward_search.
    double bidirectional_after_s = -1.0;
    /// Whether a weight w (ARA*'s epsilon, A-MHA*'s w1) inflates the heuristics' heading-aware
    /// terms too: the block abstraction, the kinematic table and the turning terms. Off (the
    /// default): the keys are g + h + (w - 1) b, with b the heading-blind part of h (the larger
    /// of the Euclidean and grid terms; an inadmissible heuristic's Dijkstra), so those terms
    /// count once (SearchProblem::hasInflationBases: every bound holds). Inflated, they reward
    /// turning early, by w times what the turn saves in h for once what it costs
    /// (docs/results/lattice.md, 1.0). On: the paper's keys, g + w h.
    bool inflate_heading_terms = false;
  };
  /// The per-goal heuristic grids kept between queries.
  struct Cache {
    int size = 2;  ///< goals whose grids are kept (each costs ~16 bytes per map cell)
    /// A planner built from the previous one after a map change keeps that one's cached grids
    /// and repairs them on the first query to their goal (HeuristicGridBuilder::repair: exact,
    /// and far quicker than computing them again unless the change reroutes most of the map).
    bool repair = true;
    /// Whether a query's grids are completed over the whole map once its search has a path, so
    /// that the next query to the same goal reuses them from any start (a robot replanning
    /// toward its goal). Off: the thread completing them stops once their keys pass the best
    /// path's cost (GoalHeuristics::stopBeyond), which the search's proof never reads beyond:
    /// the cells past it cost no memory and no time on the second core, and the next query to
    /// that goal computes its grids again. `amha plan`, which plans once, turns it off.
    bool complete_grids = true;
  };

  Robot robot;
  Motion motion;
  CostModel cost;
  Heuristics heuristics;
  Cache cache;
  /// Search from the goal back to the start (as SBPL does by default). The heuristics are
  /// then computed from the start, so the cache helps only repeated queries from one start.
  bool backward_search = false;
};

/// "kinematic", "paper" -> LatticeConfig::Inadmissible; false for anything else.
inline bool parseInadmissible(const std::string& text, LatticeConfig::Inadmissible* out) {
  if (text != "kinematic" && text != "paper") return false;
  *out = text == "paper" ? LatticeConfig::Inadmissible::kPaper
                         : LatticeConfig::Inadmissible::kKinematic;
  return true;
}
/// "kinematic", "paper".
inline const char* inadmissibleName(LatticeConfig::Inadmissible kind) {
  return kind == LatticeConfig::Inadmissible::kPaper ? "paper" : "kinematic";
}

}  // namespace lattice
}  // namespace amha
