// Fuzzes the Moving AI .map reader (through a scratch file; the first byte picks the upscale
// factor, 0 = an invalid one): every input loads as a map with the documented shape or is
// refused with a LatticeError (kMap) naming the file.
#include <cstdint>
#include <string>

#include "amha_planner/lattice/map_loaders.h"
#include "fuzz_support.h"

using namespace amha;
using namespace amha::lattice;
using amha::fuzz::finding;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int upscale = data[0] % 5;  // 0 is refused
  const std::string path = fuzz::writeScratch("fuzz.map", data + 1, size - 1);
  try {
    const GridMap m = loadMovingAiMap(path, 0.1, upscale);
    if (upscale < 1) finding("upscale 0 accepted");
    if (m.width <= 0 || m.height <= 0 || m.width % upscale != 0 || m.height % upscale != 0 ||
        m.cost.size() != static_cast<std::size_t>(m.width) * m.height) {
      finding("map with an inconsistent size");
    }
    for (std::uint8_t c : m.cost) {
      if (c != kFreeCost && c != kLethalCost) finding("cost other than free or lethal");
    }
  } catch (const LatticeError& e) {
    if (e.kind() != LatticeError::Kind::kMap) finding(std::string("wrong error kind: ") + e.what());
    if (std::string(e.what()).rfind(path, 0) != 0)
      finding(std::string("error does not name the file: ") + e.what());
  }
  return 0;
}
