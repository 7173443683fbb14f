// The backward side of a bidirectional proof: an A* from the goal, on a helper thread, whose
// progress raises the forward search's anchor.
//
// The backward search (LatticeProblem searching backward, its anchor e_b measured from the
// start, consistent) expands states in the order of its keys g_b + e_b, g_b being the exact
// cost to the goal (h*) of the state it expands. When its smallest key is K, every state with
// h* + e_b < K has been expanded, and every other state has h* >= K - e_b. So, for a snapshot K
// of that key and the states expanded by then,
//   h_K(s) = min(h*(s), K - e_b(s))
// is h* where the backward search expanded s (there h* <= K - e_b) and K - e_b elsewhere (there
// it is below h*): admissible, and consistent as the minimum of two consistent functions (h*,
// and K - e_b because e_b is consistent: e_b(q) <= e_b(p) + c(p, q) for an edge p -> q). The
// forward anchor takes max(h_0, h_K); a larger K gives a larger h_K, so the forward search may
// take up a new snapshot whenever the key has risen (SearchProblem::upgradeHeuristics).
//
// Once K reaches the cost of the forward search's best path that path is optimal, and h_K
// proves it: for every state s on OPEN, g(s) + h_K(s) >= g*(s) + K - e_b(s) >= K, e_b being
// a lower bound on g*. The backward search then stops (`bound`).
//
// Measured (docs/results/smac.md, "What would prove within 3x at 2.5 cm"): the proofs that turn
// in little room, where the forward anchor is weakest near one end, come 1.5-3.8 times sooner;
// where the backward search adds nothing its thread costs the forward one 10-17 %, which is why
// it starts only after the proof has run for LatticeConfig::Heuristics::bidirectional_after_s.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>

#include "amha_planner/lattice/detail/heuristic_grids.h"
#include "amha_planner/lattice/detail/zeroed_array.h"

namespace amha {
namespace lattice {

class LatticeProblem;

/// Written by the backward search's thread (LatticeProblem::expanded), read by the forward one
/// (LatticeProblem::anchor). `closed` is written with relaxed atomic stores and `key` stored with
/// release after them, so a reader that loaded `key` (acquire) sees every state closed before.
struct BackwardBound {
  /// Per lattice state ((y * width + x) * headings + heading): 1 + h*, once expanded; 0 before.
  ZeroedArray<std::uint32_t> closed;
  std::atomic<std::uint64_t> key{0};  ///< every state with h* + e_b below it is in `closed`
  std::atomic<bool> ready{false};     ///< `closed`, `start_anchor` and the sizes are set
  std::atomic<bool> stop{false};      ///< the backward search's cancel flag
  /// The forward search's best path cost: the backward search stops once its key reaches it.
  std::atomic<std::uint64_t> bound{UINT64_MAX};
  /// e_b for the forward thread: its own problem over the backward grids (read-only there).
  std::unique_ptr<const LatticeProblem> start_anchor;
  int width = 0, headings = 0;

  std::size_t index(int x, int y, int heading) const {
    return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
            static_cast<std::size_t>(x)) *
               static_cast<std::size_t>(headings) +
           static_cast<std::size_t>(heading);
  }
};

}  // namespace lattice
}  // namespace amha
