// The N x N sliding-tile puzzle as a SearchProblem.
//
// Storage: every discovered state lives in a chunked flat arena as its packed board (B bits a
// tile: 4 for N <= 4, 5 for N = 5, 6 for N = 6..8, 7 for N = 9; 8 bytes for the 15-puzzle,
// 40 for the 48-puzzle, 48 for the 63-puzzle) plus one 32-bit word holding its MD, LC/2, MT
// and blank position. An open-addressing table (linear probing, 4-byte slots) maps boards to
// dense StateIds. No per-state heap objects; chunks are allocated 64 Ki states at a time.
//
// Successors are generated without allocation. A child's MD, MT and LC are updated from its
// parent's: moving tile t changes MD and MT by table look-ups, and LC only in the one line
// (the column for a horizontal move, the row for a vertical one) that t enters or leaves, and
// only if that is t's goal line (a horizontal move keeps the order of the row's tiles).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "amha_planner/search/problem.h"
#include "amha_planner/tiles/board.h"
#include "amha_planner/tiles/heuristics.h"

namespace amha {
namespace tiles {

class TilesProblem : public SearchProblem {
 public:
  /// Heuristic 0 is MD + LC; heuristic i >= 1 is weights[i-1] applied to (MD, LC, MT).
  /// Throws std::invalid_argument for a malformed or unsolvable start board.
  static std::unique_ptr<TilesProblem> create(const Board& start, std::vector<TermWeights> weights);

  int size() const { return size_; }
  const std::vector<TermWeights>& weights() const { return weights_; }
  std::size_t numHeuristics() const override { return 1 + weights_.size(); }
  /// Unit moves and heuristics below a few thousand: the search may use bucket queues.
  bool smallIntegerKeys() const override { return true; }

  /// The board of a discovered state.
  virtual Board board(StateId s) const = 0;
  /// MD, LC and MT of a discovered state (as cached: computed incrementally).
  virtual HeuristicTerms terms(StateId s) const = 0;
  /// States discovered so far (ids are 0 .. numStates()-1).
  virtual std::size_t numStates() const = 0;
  /// Bytes held for the state arena (boards + terms) and for the hash table, separately.
  virtual std::size_t arenaBytes() const = 0;
  virtual std::size_t tableBytes() const = 0;
  std::size_t memoryBytes() const override { return arenaBytes() + tableBytes(); }

 protected:
  TilesProblem(int size, std::vector<TermWeights> weights)
      : size_(size), weights_(std::move(weights)) {}

  int size_;
  std::vector<TermWeights> weights_;
};

}  // namespace tiles
}  // namespace amha
