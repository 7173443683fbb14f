// Fuzzes the tile instance reader: every text either parses into solvable, well-formed boards
// that write out and read back unchanged, or is refused with an InstanceError naming the input
// and (for a bad line) the line. The first byte picks the expected board size (0 = any).
#include <cstdint>
#include <string>

#include "amha_planner/tiles/board.h"
#include "amha_planner/tiles/heuristics.h"
#include "amha_planner/tiles/instances.h"
#include "fuzz_support.h"

using namespace amha::tiles;
using amha::fuzz::finding;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int expected = data[0] % 12;  // 0: any; 1, 2, 10, 11: sizes the reader must refuse
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  std::vector<Instance> instances;
  try {
    instances = parseInstances(text, "fuzz.txt", expected);
  } catch (const InstanceError& e) {
    if (std::string(e.what()).rfind("fuzz.txt", 0) != 0)
      finding(std::string("error does not name the input: ") + e.what());
    return 0;
  }
  if (instances.empty()) finding("no instances and no error");
  const int n = instances.front().start.size;
  if (expected != 0 && n != expected) finding("board size differs from the expected size");
  for (const Instance& inst : instances) {
    if (inst.start.size != n) finding("boards of different sizes");
    if (!boardError(inst.start).empty()) finding("malformed board accepted");
    if (!isSolvable(inst.start)) finding("unsolvable board accepted");
    if (inst.optimal && *inst.optimal < manhattanDistance(inst.start))
      finding("optimal below the Manhattan distance");
  }
  const std::vector<Instance> back =
      parseInstances(formatInstances(instances), "written.txt", expected);
  if (back.size() != instances.size()) finding("round trip changed the count");
  for (std::size_t i = 0; i < back.size(); ++i) {
    if (back[i].id != instances[i].id || back[i].start.tiles != instances[i].start.tiles ||
        back[i].optimal != instances[i].optimal) {
      finding("round trip changed an instance");
    }
  }
  return 0;
}
