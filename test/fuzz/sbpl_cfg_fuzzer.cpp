// Fuzzes the SBPL .cfg environment reader (through a scratch file): every input loads with the
// documented shape and cost mapping or is refused with a LatticeError (kMap) naming the file.
#include <cmath>
#include <cstdint>
#include <string>

#include "amha_planner/lattice/map_loaders.h"
#include "fuzz_support.h"

using namespace amha;
using namespace amha::lattice;
using amha::fuzz::finding;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::writeScratch("fuzz.cfg", data, size);
  try {
    const SbplEnvironment env = loadSbplEnvironment(path);
    const GridMap& m = env.map;
    if (m.width <= 0 || m.height <= 0 ||
        m.cost.size() != static_cast<std::size_t>(m.width) * m.height) {
      finding("map with an inconsistent size");
    }
    if (!(m.resolution > 0.0) || !std::isfinite(m.resolution))
      finding("resolution not positive and finite");
    if (env.num_theta_dirs < 1 || env.obsthresh < 1 || !(env.nominal_speed > 0.0) ||
        env.time_to_turn_45 < 0.0) {
      finding("header value out of its documented range");
    }
    for (std::uint8_t c : m.cost) {
      if (c == kUnknownCost) finding("unknown cost from a .cfg");
    }
  } catch (const LatticeError& e) {
    if (e.kind() != LatticeError::Kind::kMap) finding(std::string("wrong error kind: ") + e.what());
    if (std::string(e.what()).rfind(path, 0) != 0)
      finding(std::string("error does not name the file: ") + e.what());
  }
  return 0;
}
