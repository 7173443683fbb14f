// Moves of the heuristics' 2-D grids (8- or 16-connected), and the shortest walk along them
// inside a set of cells: what the anchor's grid scale is computed from (LatticeGraph) and what
// the grids step by (HeuristicGridBuilder).
#pragma once

#include <vector>

#include "amha_planner/lattice/detail/footprint.h"

namespace amha {
namespace lattice {

/// A grid move: from a cell to (dx, dy), allowed only if every required cell (the cells the
/// straight segment between the two centres meets, both ends included) is passable; its cost
/// uses the worst of those cells. Exception, `either_side`: a diagonal step's segment touches
/// its two side cells only at their shared corner, so it needs its two ends and *one* passable
/// side cell, and its cost uses the cheaper passable side. (Demanding both sides cost the
/// anchor a quarter of its scale on pr2.mprim, whose 22.5-degree primitives pass exactly
/// through cell corners.)
struct GridMove {
  int dx = 0, dy = 0;
  double length = 0.0;  ///< cells
  std::vector<CellOffset> required;
  bool either_side =
      false;  ///< required = the two ends + the two side cells, one of which suffices
};

/// The 8 neighbours (connectivity 8) or the 8 neighbours and the 8 knight moves (16).
std::vector<GridMove> gridMoves(int connectivity);

/// Shortest walk (in cells of length) from (0, 0) to `to` using `moves` whose required cells
/// all lie in `cells`; infinity if there is none.
double walkLength(const std::vector<CellOffset>& cells, CellOffset to,
                  const std::vector<GridMove>& moves);

}  // namespace lattice
}  // namespace amha
