// Fuzzes the map_server loader (YAML + image). The input is a YAML document, a NUL byte, then
// the bytes of the image file (any format OpenCV reads); both are written to a scratch
// directory, the image as "map.img" (the seeds' YAML names it). Every input must either load
// as a map with the documented shape or be refused with a LatticeError (kMap) naming the file.
#include <cstdint>
#include <cstring>
#include <string>

#include "amha_planner/lattice/map_loaders.h"
#include "fuzz_support.h"

using namespace amha;
using namespace amha::lattice;
using amha::fuzz::finding;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const void* nul = std::memchr(data, 0, size);
  const std::size_t yaml_size =
      nul != nullptr ? static_cast<const std::uint8_t*>(nul) - data : size;
  const std::string yaml = fuzz::writeScratch("map.yaml", data, yaml_size);
  const std::size_t image_offset = nul != nullptr ? yaml_size + 1 : size;
  const std::string image = fuzz::writeScratch("map.img", data + image_offset, size - image_offset);
  (void)image;
  const std::string dir = fuzz::scratchDir() + "/";
  try {
    // Only images inside the scratch directory: the YAML may name any file (/dev/zero ...).
    const MapServerYaml y = readMapServerYaml(yaml);
    if (y.image.compare(0, dir.size(), dir) != 0 ||
        y.image.find('/', dir.size()) != std::string::npos ||
        y.image.find("..") != std::string::npos) {
      return 0;
    }
    OccupancyConversion conversion;
    conversion.unknown_is_free = (size & 1) != 0;
    const GridMap m = loadMapServerMap(yaml, conversion);
    if (m.width <= 0 || m.height <= 0 ||
        m.cost.size() != static_cast<std::size_t>(m.width) * m.height) {
      finding("map with an inconsistent size");
    }
    if (!(m.resolution > 0.0)) finding("map with a resolution that is not positive");
    for (std::uint8_t c : m.cost) {
      if (c != kFreeCost && c != kLethalCost && c != kUnknownCost && (c < 1 || c > 252))
        finding("cost out of range");
    }
  } catch (const LatticeError& e) {
    if (e.kind() != LatticeError::Kind::kMap) finding(std::string("wrong error kind: ") + e.what());
    const std::string what = e.what();
    if (what.rfind(dir, 0) != 0) finding("error does not name the file: " + what);
  }
  return 0;
}
