// Sliding-tile instances: the Korf file format (read and write) and seeded generators.
//
// File format (as ../shared/data/tiles/korf100_15puzzle.txt): lines starting with '#' and
// blank lines are ignored; every other line is one instance
//     id optimal md t0 t1 ... t(N*N-1)
// where t_k is the tile at position k (row-major), 0 is the blank, and the goal is
// 0 1 2 ... N*N-1 (blank top-left). `optimal` is the optimal solution length, or -1 if
// unknown; `md` is the Manhattan distance of the start (checked when read; -1 skips the check).
// N is inferred from the number of tiles (all lines of a file must agree).
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "amha_planner/tiles/board.h"

namespace amha {
namespace tiles {

struct Instance {
  std::string id;
  Board start;
  std::optional<int> optimal;  ///< known optimal solution length
};

/// A malformed instance file; what() names the file and line.
class InstanceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Reads an instance file. `expected_size` > 0 requires that board size. Throws InstanceError
/// for: unreadable file, non-numeric text, wrong tile count, tiles out of range, duplicate
/// tiles, an md column that disagrees with the tiles, unsolvable boards, and empty files.
std::vector<Instance> readInstances(const std::string& path, int expected_size = 0);
/// The same, from text (`name` is used in messages in place of the file name).
std::vector<Instance> parseInstances(const std::string& text, const std::string& name,
                                     int expected_size = 0);

/// Writes instances in the same format (optimal -1 when unknown). Throws std::runtime_error.
void writeInstances(const std::string& path, const std::vector<Instance>& instances,
                    const std::string& comment = "");
std::string formatInstances(const std::vector<Instance>& instances,
                            const std::string& comment = "");

/// Uniform random solvable board: a uniformly random permutation (Fisher-Yates), drawn again
/// until it is solvable, so every solvable board is equally likely. Instance `index` of `seed`
/// is generated from its own std::mt19937_64 seeded with std::seed_seq{seed, index, size}, so
/// it does not depend on how many instances are generated. Bounded draws use rejection
/// sampling on the raw generator output (portable across standard libraries).
Board randomSolvableBoard(int size, std::uint64_t seed, std::uint64_t index);

/// A random walk of `length` moves from the goal (never undoing the previous move).
Board randomWalkBoard(int size, int length, std::uint64_t seed, std::uint64_t index);

/// `count` instances named "rand<N>-s<seed>-<i>" (or "walk<N>-L<len>-s<seed>-<i>" with
/// walk_length > 0), i = 0 .. count-1.
std::vector<Instance> generateInstances(int size, int count, std::uint64_t seed,
                                        int walk_length = 0);

}  // namespace tiles
}  // namespace amha
