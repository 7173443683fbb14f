#include "amha_planner/tiles/instances.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <random>
#include <set>
#include <sstream>

#include "amha_planner/tiles/heuristics.h"

namespace amha {
namespace tiles {

namespace {

constexpr long kMaxOptimalLength = 1000000;

[[noreturn]] void fail(const std::string& where, int line, const std::string& what) {
  throw InstanceError(where + ":" + std::to_string(line) + ": " + what);
}

bool parseInt(const std::string& token, long* out) {
  const char* first = token.data();
  const char* last = first + token.size();
  const auto r = std::from_chars(first, last, *out);
  return r.ec == std::errc() && r.ptr == last;
}

std::mt19937_64 instanceRng(int size, std::uint64_t seed, std::uint64_t index) {
  std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                    static_cast<std::uint32_t>(index), static_cast<std::uint32_t>(index >> 32),
                    static_cast<std::uint32_t>(size)};
  return std::mt19937_64(seq);
}

// Uniform in [0, n) by rejection: portable, unlike std::uniform_int_distribution.
std::uint64_t uniformBelow(std::mt19937_64& rng, std::uint64_t n) {
  const std::uint64_t threshold = (0 - n) % n;  // 2^64 mod n: reject the biased low values
  for (;;) {
    const std::uint64_t x = rng();
    if (x >= threshold) return x % n;
  }
}

}  // namespace

std::vector<Instance> parseInstances(const std::string& text, const std::string& name,
                                     int expected_size) {
  std::vector<Instance> out;
  std::set<std::string> ids;
  std::istringstream in(text);
  std::string line;
  int line_no = 0, first_size_line = 0;
  int size = expected_size;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream ls(line);
    std::vector<std::string> tok;
    for (std::string t; ls >> t;) tok.push_back(t);
    if (tok.empty() || tok[0][0] == '#') continue;
    if (tok.size() < 3)
      fail(name, line_no, "expected `id optimal md tiles...`, got too few fields");
    Instance inst;
    inst.id = tok[0];
    long optimal = 0, md = 0;
    // Bounded so that it fits the int it is stored in (the longest optimal 9x9 solution is far
    // below the bound).
    if (!parseInt(tok[1], &optimal) || optimal < -1 || optimal > kMaxOptimalLength) {
      fail(name, line_no,
           "optimal length '" + tok[1] + "' is not an integer in -1.." +
               std::to_string(kMaxOptimalLength));
    }
    if (!parseInt(tok[2], &md) || md < -1) {
      fail(name, line_no, "md '" + tok[2] + "' is not an integer >= -1");
    }
    const int n_tiles = static_cast<int>(tok.size()) - 3;
    if (size > 0) {
      if (n_tiles != size * size) {
        fail(name, line_no,
             "expected " + std::to_string(size * size) + " tiles for a " + std::to_string(size) +
                 "x" + std::to_string(size) + " board" +
                 (first_size_line > 0 ? " (as on line " + std::to_string(first_size_line) + ")"
                                      : std::string(" (the size requested)")) +
                 ", got " + std::to_string(n_tiles));
      }
    } else {
      const int root = static_cast<int>(std::lround(std::sqrt(static_cast<double>(n_tiles))));
      if (root * root != n_tiles || root < kMinSize || root > kMaxSize) {
        fail(name, line_no,
             "wrong tile count: " + std::to_string(n_tiles) +
                 " tiles is not N*N for a board size N in 3..9");
      }
      size = root;
      first_size_line = line_no;
    }
    inst.start.size = size;
    inst.start.tiles.resize(static_cast<std::size_t>(n_tiles));
    for (int k = 0; k < n_tiles; ++k) {
      long t = 0;
      if (!parseInt(tok[3 + k], &t)) {
        fail(name, line_no,
             "tile " + std::to_string(k) + " '" + tok[3 + k] + "' is not an integer");
      }
      if (t < 0 || t >= n_tiles) {
        fail(name, line_no,
             "tile " + std::to_string(t) + " at position " + std::to_string(k) +
                 " is out of range 0.." + std::to_string(n_tiles - 1));
      }
      inst.start.tiles[k] = static_cast<std::uint8_t>(t);
    }
    const std::string err = boardError(inst.start);
    if (!err.empty()) fail(name, line_no, err);
    if (md >= 0 && md != manhattanDistance(inst.start)) {
      fail(name, line_no,
           "md column says " + std::to_string(md) + " but the tiles' Manhattan distance is " +
               std::to_string(manhattanDistance(inst.start)) +
               " (a transcription error? use -1 to skip the check)");
    }
    if (!isSolvable(inst.start)) {
      fail(name, line_no,
           "instance '" + inst.id +
               "' is unsolvable (wrong permutation parity for the goal 0 1 2 ...)");
    }
    if (optimal >= 0) {
      if (optimal < manhattanDistance(inst.start)) {
        fail(name, line_no,
             "optimal length " + std::to_string(optimal) +
                 " is below the Manhattan distance, which is a lower bound");
      }
      inst.optimal = static_cast<int>(optimal);
    }
    if (!ids.insert(inst.id).second) fail(name, line_no, "duplicate instance id '" + inst.id + "'");
    out.push_back(std::move(inst));
  }
  if (out.empty()) throw InstanceError(name + ": no instances (only comments or blank lines)");
  return out;
}

std::vector<Instance> readInstances(const std::string& path, int expected_size) {
  std::ifstream in(path);
  if (!in) throw InstanceError(path + ": cannot open the instance file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InstanceError(path + ": read error");
  return parseInstances(text.str(), path, expected_size);
}

std::string formatInstances(const std::vector<Instance>& instances, const std::string& comment) {
  std::ostringstream out;
  std::istringstream lines(comment);
  for (std::string l; std::getline(lines, l);) out << "# " << l << "\n";
  out << "# Format: id optimal md t0 .. t(N*N-1); t_k = tile at position k, row-major; 0 = blank;"
         " goal 0 1 2 ...; optimal -1 = unknown\n";
  for (const Instance& inst : instances) {
    out << inst.id << " " << (inst.optimal ? *inst.optimal : -1) << " "
        << manhattanDistance(inst.start);
    for (std::uint8_t t : inst.start.tiles) out << " " << static_cast<int>(t);
    out << "\n";
  }
  return out.str();
}

void writeInstances(const std::string& path, const std::vector<Instance>& instances,
                    const std::string& comment) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << formatInstances(instances, comment);
  if (!out) throw std::runtime_error("error writing " + path);
}

Board randomSolvableBoard(int size, std::uint64_t seed, std::uint64_t index) {
  std::mt19937_64 rng = instanceRng(size, seed, index);
  Board b = goalBoard(size);
  do {
    for (std::size_t i = b.tiles.size() - 1; i > 0; --i) {
      std::swap(b.tiles[i], b.tiles[uniformBelow(rng, i + 1)]);
    }
  } while (!isSolvable(b));
  return b;
}

Board randomWalkBoard(int size, int length, std::uint64_t seed, std::uint64_t index) {
  std::mt19937_64 rng = instanceRng(size, seed, index ^ 0x5741'4c4bULL);
  Board b = goalBoard(size);
  int blank = 0, previous = -1;
  for (int step = 0; step < length; ++step) {
    int options[4], n_options = 0;
    const int r = blank / size, c = blank % size;
    const int cand[4] = {r > 0 ? blank - size : -1, r < size - 1 ? blank + size : -1,
                         c > 0 ? blank - 1 : -1, c < size - 1 ? blank + 1 : -1};
    for (int q : cand) {
      if (q >= 0 && q != previous) options[n_options++] = q;
    }
    const int q = options[uniformBelow(rng, static_cast<std::uint64_t>(n_options))];
    std::swap(b.tiles[blank], b.tiles[q]);
    previous = blank;
    blank = q;
  }
  return b;
}

std::vector<Instance> generateInstances(int size, int count, std::uint64_t seed, int walk_length) {
  std::vector<Instance> out;
  out.reserve(static_cast<std::size_t>(std::max(count, 0)));
  for (int i = 0; i < count; ++i) {
    Instance inst;
    if (walk_length > 0) {
      inst.id = "walk" + std::to_string(size) + "-L" + std::to_string(walk_length) + "-s" +
                std::to_string(seed) + "-" + std::to_string(i);
      inst.start = randomWalkBoard(size, walk_length, seed, static_cast<std::uint64_t>(i));
    } else {
      inst.id =
          "rand" + std::to_string(size) + "-s" + std::to_string(seed) + "-" + std::to_string(i);
      inst.start = randomSolvableBoard(size, seed, static_cast<std::uint64_t>(i));
    }
    out.push_back(std::move(inst));
  }
  return out;
}

}  // namespace tiles
}  // namespace amha
